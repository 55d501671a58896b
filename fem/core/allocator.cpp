#include "fem/core/allocator.hpp"

#include <malloc.h>

#include <limits>

namespace softarm::fem {

void keep_freed_memory_mapped() {
#if defined(__GLIBC__)
  // No block is served by its own mmap, so a freed block goes back to malloc's free
  // lists (mallopt's M_MMAP_THRESHOLD cannot do this: it is capped at 32 MiB, below
  // the tangent's arrays). Threads' arenas fall back to the main heap for such blocks.
  mallopt(M_MMAP_MAX, 0);
  // Shrink the heap only past 2 GiB of free top: a Newton iteration frees what the next one allocates again.
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
#endif
}

}  // namespace softarm::fem
