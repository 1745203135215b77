// A Meld program from its source text, compiled as meldc would, for tests that run it in-process
// (identityNodes: node ids are the source's, as on a robot world, instead of §6.1's renumbering).
#pragma once

#include <boost/test/unit_test.hpp>
#include <memory>
#include <sstream>
#include <string>

#include "meldc/compile.hpp"
#include "meldc/diagnostics.hpp"
#include "temp_dir.hpp"

inline std::unique_ptr<meldvm::Program> compileSource(const std::string& source, bool identityNodes = false) {
  TempDir dir;
  const std::string path = dir.write("prog.meld", source);
  meldc::SourceManager sources;
  std::ostringstream errors;
  meldc::Diagnostics diag(sources, errors);
  meldc::FrontEndInput input{path, {}, {}};
  input.identityNodes = identityNodes;
  std::unique_ptr<meldvm::Program> p = meldc::compileProgram(input, sources, diag);
  BOOST_REQUIRE_MESSAGE(p, "compile errors:\n" << errors.str());
  return p;
}
