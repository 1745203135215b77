// A Meld program from its source text, compiled as meldc would (the threads tests' programs).
#pragma once

#include <boost/test/unit_test.hpp>
#include <memory>
#include <sstream>
#include <string>

#include "../meldc/temp_dir.hpp"
#include "meldc/compile.hpp"
#include "meldc/diagnostics.hpp"

inline std::unique_ptr<meldvm::Program> compile(const std::string& source) {
  TempDir dir;
  const std::string path = dir.write("prog.meld", source);
  meldc::SourceManager sources;
  std::ostringstream errors;
  meldc::Diagnostics diag(sources, errors);
  std::unique_ptr<meldvm::Program> p = meldc::compileProgram({path, {}, {}}, sources, diag);
  BOOST_REQUIRE_MESSAGE(p, "compile errors:\n" << errors.str());
  return p;
}
