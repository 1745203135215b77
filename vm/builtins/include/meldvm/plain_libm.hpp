// exp and log for the built-ins, without glibc's errno wrapper where the build found its entry
// points (MELD_GLIBC_MATH_ENTRIES, vm/builtins/CMakeLists.txt): the same functions that exp and log
// call, so the same bits for every input, only errno is never set. The wrapper was 16 instructions
// of every exp: 5 % of belief-propagation-50's run, which calls exp 17.8 million times (callgrind).
// Elsewhere these are std::exp and std::log.
#pragma once

#include <cmath>

#if MELD_GLIBC_MATH_ENTRIES
// glibc keeps these versions for binaries built against 2.15 to 2.30 (math-finite.h); on x86-64
// they resolve, by ifunc, to the implementation that the wrappers of exp@2.29 and log@2.29 call.
extern "C" double meldvm_glibc_exp_entry(double) noexcept;
extern "C" double meldvm_glibc_log_entry(double) noexcept;
__asm__(".symver meldvm_glibc_exp_entry, __exp_finite@GLIBC_2.15");
__asm__(".symver meldvm_glibc_log_entry, __log_finite@GLIBC_2.15");
#endif

namespace meldvm {

#if MELD_GLIBC_MATH_ENTRIES
inline double plainExp(double x) { return meldvm_glibc_exp_entry(x); }
inline double plainLog(double x) { return meldvm_glibc_log_entry(x); }
#else
inline double plainExp(double x) { return std::exp(x); }
inline double plainLog(double x) { return std::log(x); }
#endif

}  // namespace meldvm
