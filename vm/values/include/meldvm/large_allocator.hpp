// The VM's big arrays use the project's one large-page allocator (support/large_allocator.hpp).
#pragma once

#include "support/large_allocator.hpp"
#include "support/large_buffer.hpp"

namespace meldvm {

using support::LargeAllocator;
using support::LargeBuffer;
using support::LargeVector;

}  // namespace meldvm
