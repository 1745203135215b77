#include "meldvm/large_allocator.hpp"

#include <sys/mman.h>

#include <cstdlib>

namespace meldvm::detail {

void* allocateLarge(std::size_t bytes) {
  const std::size_t rounded = (bytes + kHugePage - 1) & ~(kHugePage - 1);
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  (void)madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure only means small pages
#endif
  return p;
}

void freeLarge(void* p) { std::free(p); }

}  // namespace meldvm::detail
