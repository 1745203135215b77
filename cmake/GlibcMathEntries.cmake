# meld_check_glibc_math_entries(VAR): whether glibc's exp and log entry points without the errno
# wrapper (__exp_finite@GLIBC_2.15, __log_finite@GLIBC_2.15) link and give what exp and log give
# (vm/builtins/include/meldvm/plain_libm.hpp uses them when VAR is true).
include(CheckCXXSourceRuns)
function(meld_check_glibc_math_entries var)
  set(CMAKE_REQUIRED_QUIET ON)
  check_cxx_source_runs([=[
#include <cmath>
extern "C" double meldvm_glibc_exp_entry(double) noexcept;
extern "C" double meldvm_glibc_log_entry(double) noexcept;
__asm__(".symver meldvm_glibc_exp_entry, __exp_finite@GLIBC_2.15");
__asm__(".symver meldvm_glibc_log_entry, __log_finite@GLIBC_2.15");
int main() {
  volatile double xs[] = {-745.2, -1.5, -1e-300, 0.0, 0.3, 1.0, 2.5, 709.7, 710.0};
  for (double x : xs) {
    if (meldvm_glibc_exp_entry(x) != std::exp(x)) return 1;
    if (x > 0 && meldvm_glibc_log_entry(x) != std::log(x)) return 1;
  }
  return 0;
}
]=] ${var})
  set(${var} ${${var}} PARENT_SCOPE)
endfunction()
