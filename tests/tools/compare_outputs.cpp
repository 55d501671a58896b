// compare_outputs DIR_A DIR_B [--rtol R] [--atol A] [--show N]
//
// Compares two runs' result directories number by number (tests/support/output_comparison.hpp):
// prints each file's verdict and the first N differences (20 by default), and exits 0 when every
// number is within tolerance and every word equal, 1 when not, 2 on bad usage.
// scripts/compare_revisions.sh runs the thesis scenes and a short design with two builds and calls it.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "support/output_comparison.hpp"

namespace {
int usage(const char* why) {
  std::fprintf(stderr, "compare_outputs: %s\nusage: compare_outputs DIR_A DIR_B [--rtol R (1e-6)] [--atol A (1e-12)] [--show N (20)]\n", why);
  return 2;
}

bool parse_number(const char* text, double& value) {
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0' && value >= 0 && value < 1;
}
}  // namespace

int main(int argc, char** argv) {
  softarm::test::ComparisonTolerance tolerance;
  std::string dirs[2];
  int n_dirs = 0;
  long show = 20;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--rtol" || a == "--atol") && i + 1 < argc) {
      double& target = a == "--rtol" ? tolerance.relative : tolerance.absolute;
      if (!parse_number(argv[++i], target)) return usage((a + " " + argv[i] + ": give a number in [0, 1)").c_str());
    } else if (a == "--show" && i + 1 < argc) {
      show = std::strtol(argv[++i], nullptr, 10);
    } else if (a.rfind("--", 0) == 0 || n_dirs == 2) {
      return usage(("unknown argument '" + a + "'").c_str());
    } else {
      dirs[n_dirs++] = a;
    }
  }
  if (n_dirs != 2) return usage("give two result directories");
  const auto result = softarm::test::compare_output_directories(dirs[0], dirs[1], tolerance);
  if (result.files_compared == 0 && result.differences.empty()) return usage("no files under either directory");
  long shown = 0;
  for (const auto& d : result.differences)
    if (shown++ < show) std::printf("  %s: %s: %s | %s\n", d.file.c_str(), d.where.c_str(), d.first.c_str(), d.second.c_str());
  std::printf("%s vs %s: %d files, %ld numbers; largest relative difference %.3g; %zu difference(s) beyond rtol %g\n",
              dirs[0].c_str(), dirs[1].c_str(), result.files_compared, result.numbers_compared,
              result.largest_relative_difference, result.differences.size(), tolerance.relative);
  return result.differences.empty() ? 0 : 1;
}
