#include "meldc/frontend_loader.hpp"

#include <cstdlib>
#include <ostream>

#include "meldc/frontend_module.h"
#include "support/toolchain_module.hpp"

namespace meldc {

namespace {

// The module stays loaded for the rest of the process.
meld_frontend_compile_fn loadModule() {
  const std::string what = "Meld front end module";
  std::string path;
  try {
    path = support::findToolchainModule("MELD_FRONTEND_MODULE", "libmeld_frontend.so",
                                        MELD_FRONTEND_MODULE_BUILD_PATH, what);
  } catch (const std::runtime_error& e) {
    throw FrontEndModuleError(
        std::string(e.what()) +
        (std::getenv("MELD_FRONTEND_MODULE") ? "" : "; compile the program with meldc and run the .mbc"));
  }
  try {
    void* handle = support::openToolchainModule(path, what, "meld_frontend_version",
                                                MELD_FRONTEND_MODULE_VERSION, {"meld_frontend_compile"});
    return support::moduleFunction<meld_frontend_compile_fn>(handle, "meld_frontend_compile");
  } catch (const std::runtime_error& e) {
    throw FrontEndModuleError(e.what());
  }
}

}  // namespace

std::unique_ptr<meldvm::Program> compileThroughModule(
    const std::string& path, const std::vector<std::string>& includeDirs,
    const std::vector<std::pair<std::string, std::string>>& defines, std::ostream& diagnostics) {
  const meld_frontend_compile_fn compile = loadModule();
  std::vector<const char*> dirs, names, values;
  for (const std::string& d : includeDirs) dirs.push_back(d.c_str());
  for (const auto& [name, value] : defines) {
    names.push_back(name.c_str());
    values.push_back(value.c_str());
  }
  const auto report = [](const char* text, size_t size, void* context) {
    static_cast<std::ostream*>(context)->write(text, std::streamsize(size));
  };
  void* program = nullptr;
  char error[2048] = "";
  const int status = compile(path.c_str(), dirs.data(), dirs.size(), names.data(), values.data(),
                             names.size(), +report, &diagnostics, &program, error, sizeof error);
  if (status == MELD_FRONTEND_INTERNAL_ERROR) throw FrontEndInternalError(error);
  // The module built the Program from the same sources with the same compiler: it is this
  // process's type, and ours to delete.
  return std::unique_ptr<meldvm::Program>(
      status == MELD_FRONTEND_COMPILED ? static_cast<meldvm::Program*>(program) : nullptr);
}

}  // namespace meldc
