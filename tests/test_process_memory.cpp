// The process set-up of softarm's main, which the test binary's main shares (fem/core/allocator.hpp):
// where the kernel gives transparent huge pages only on request, the process has restarted with
// glibc's malloc asking for them, and a large array's pages are in fact huge ones.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {
std::string first_line(const char* path) {
  std::string line;
  std::getline(std::ifstream(path), line);
  return line;
}
/// AnonHugePages of the whole process, kB (/proc/self/smaps_rollup); -1 where it is not there.
long anon_huge_pages_kB() {
  std::ifstream in("/proc/self/smaps_rollup");
  for (std::string key; in >> key;) {
    if (key == "AnonHugePages:") {
      long kB = -1;
      in >> kB;
      return kB;
    }
    in.ignore(1 << 20, '\n');
  }
  return -1;
}
}  // namespace

TEST_CASE("The process asks for huge pages where the kernel gives them on request, and gets them", "[process]") {
#if defined(__SANITIZE_ADDRESS__)
  SUCCEED("AddressSanitizer's allocator replaces glibc's malloc: its tunables do not apply");
#else
  const std::string mode = first_line("/sys/kernel/mm/transparent_hugepage/enabled");
  const char* preload = std::getenv("LD_PRELOAD");
  if (mode.find("[madvise]") == std::string::npos || (preload && std::string(preload).find("vgpreload") != std::string::npos)) {
    WARN("transparent huge pages: '" << mode << "'; nothing is asked for here");
    return;
  }
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  INFO("GLIBC_TUNABLES=" << (tunables ? tunables : "(unset)"));
  REQUIRE(tunables);
  const std::string set = tunables;
  if (set.find("glibc.malloc.hugetlb=1") == std::string::npos) {
    REQUIRE(set.find("glibc.malloc.hugetlb") != std::string::npos);  // the user's own choice, kept
    WARN("the tunable was set before the start: " << set);
    return;
  }
  const long before = anon_huge_pages_kB();
  REQUIRE(before >= 0);
  std::vector<char> big(std::size_t{64} << 20);  // 64 MiB, zeroed: every page touched
  const long after = anon_huge_pages_kB();
  INFO("AnonHugePages " << before << " kB before the array, " << after << " kB with it");
  CHECK(after - before >= 32 * 1024);  // at least half of it in 2 MiB pages
  CHECK(big[big.size() / 2] == 0);
#endif
}
