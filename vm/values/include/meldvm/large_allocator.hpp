// The VM's big arrays use the project's one large-page allocator (support/large_allocator.hpp).
#pragma once

#include "support/large_allocator.hpp"

namespace meldvm {

using support::LargeAllocator;
using support::LargeVector;

}  // namespace meldvm
