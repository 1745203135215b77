// vsim --program: a Meld program as the block program of every block (the VM behind the block
// ABI, vm/robots/include/meldvm/block_runtime.hpp).
#pragma once

#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "meldvm/program.hpp"

namespace vsim {

// A .meld file is compiled with node ids = block ids (robots: the program runs on a world's blocks;
// false: on its own graph, as `meld` runs it, for the multicore target); compile errors go to
// `diagnostics` in the usual file:line:col form (nullptr: discarded); a .mbc file is loaded and
// verified. Throws ProgramLoadError.
class ProgramLoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
std::unique_ptr<meldvm::Program> loadMeldProgram(const std::string& path,
                                                 const std::vector<std::string>& includeDirs,
                                                 std::ostream* diagnostics, bool robots = true);

}  // namespace vsim
