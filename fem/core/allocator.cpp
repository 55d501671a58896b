#include "fem/core/allocator.hpp"

#include <malloc.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>

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

void restart_with_huge_pages(char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  std::string mode;
  std::getline(std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"), mode);
  if (mode.find("[madvise]") == std::string::npos) return;  // always: the heap has them; never: none to get
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string before = tunables ? tunables : "";
  if (before.find("glibc.malloc.hugetlb") != std::string::npos) return;
  // valgrind runs the program with its preload libraries; an exec would run it natively, unchecked.
  const char* preload = std::getenv("LD_PRELOAD");
  if (preload && std::string(preload).find("vgpreload") != std::string::npos) return;
  const std::string after = (before.empty() ? "" : before + ":") + "glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", after.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // The exec failed (no /proc, say): go on with 4 KiB pages, and the environment as it was.
  if (tunables) setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
}

}  // namespace softarm::fem
