// libmeld_frontend.so: compileProgram behind the C seam of frontend_module.h, for meld, which
// loads it only for .meld files (frontend_loader.cpp). Only the functions below are exported.
#include "meldc/frontend_module.h"

#include <exception>
#include <sstream>

#include "meldc/compile.hpp"
#include "support/toolchain_module.hpp"

#define MELD_FRONTEND_EXPORT extern "C" __attribute__((visibility("default")))

using support::copyModuleMessage;

MELD_FRONTEND_EXPORT int meld_frontend_version() { return MELD_FRONTEND_MODULE_VERSION; }

MELD_FRONTEND_EXPORT int meld_frontend_compile(const char* path, const char* const* include_dirs,
                                               size_t include_count, const char* const* define_names,
                                               const char* const* define_values, size_t define_count,
                                               meld_frontend_report report, void* context, void** program,
                                               char* error, size_t error_size) {
  std::ostringstream text;
  int status = MELD_FRONTEND_ERRORS;
  try {
    meldc::FrontEndInput input;
    input.path = path;
    input.includeDirs.assign(include_dirs, include_dirs + include_count);
    for (size_t i = 0; i < define_count; ++i) input.defines.emplace_back(define_names[i], define_values[i]);
    meldc::SourceManager sources;
    meldc::Diagnostics diag(sources, text);
    if (auto compiled = meldc::compileProgram(std::move(input), sources, diag)) {
      *program = compiled.release();
      status = MELD_FRONTEND_COMPILED;
    }
  } catch (const meldc::InternalCompilerError& e) {
    copyModuleMessage(e.what(), error, error_size);
    status = MELD_FRONTEND_INTERNAL_ERROR;
  } catch (const std::exception& e) {
    copyModuleMessage(e.what(), error, error_size);
    status = MELD_FRONTEND_INTERNAL_ERROR;
  }
  const std::string diagnostics = text.str();
  if (report && !diagnostics.empty()) report(diagnostics.data(), diagnostics.size(), context);
  return status;
}
