// vsim --target multicore --program P.meld --cores N [-- ARGS]: the Meld program on a simulated
// chip of N cores (targets/multicore), no world file. Prints the predicted run time, the speedup
// over one core and each core's use; --dump prints the final facts as `meld --dump` does; with
// several core counts (--cores 1,2,4,...), one line per count. Returns vsim's exit code.
#pragma once

#include "meld_program.hpp"
#include "options.hpp"

namespace vsim {

// `jit`: compiles the program to native code for --jit (nullptr: --jit is refused).
int runMulticore(const Options& options, const NativeCompiler* jit = nullptr);

}  // namespace vsim
