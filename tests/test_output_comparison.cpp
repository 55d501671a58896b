// The before/after comparison of two runs' outputs (tests/support/output_comparison.hpp, behind
// scripts/compare_revisions.sh): it must see a changed result anywhere, and only a changed result.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/output_comparison.hpp"

namespace fs = std::filesystem;
using softarm::test::compare_output_directories;
using softarm::test::ComparisonTolerance;

namespace {
void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

/// A run's outputs in miniature: a summary, a CSV whose text field holds a comma, a VTU.
void write_run(const fs::path& dir, double extension_mm, double seconds, const std::string& phase,
               const std::string& point) {
  write(dir / "summary.json", "{\"extension_mm\": " + std::to_string(extension_mm) + ", \"time_s\": " +
                                  std::to_string(seconds) + ", \"cell_seconds_summed\": " + std::to_string(2 * seconds) +
                                  ", \"diagnosis\": \"reached 206.8 kPa in " +
                                  std::to_string(seconds) + " s\", \"curve\": [0.0, 1.5]}");
  write(dir / "history.csv", "evaluation,phase,objective,seconds\n1,\"" + phase + "\",0.25," + std::to_string(seconds) + "\n");
  write(dir / "mesh" / "deformed.vtu", "<DataArray type=\"Float64\">\n" + point + "\n</DataArray>\n");
}
}  // namespace

TEST_CASE("the before/after comparison finds a changed result and only that", "[compare]") {
  const fs::path root = fs::temp_directory_path() / ("softarm_compare_" + std::to_string(getpid()));
  fs::remove_all(root);
  const std::string phase = "tube_material=dragon_skin_30, sheath_material=dragon_skin_30: start 1";
  write_run(root / "a", 12.5, 3.0, phase, "0 1.25 2.5");
  const ComparisonTolerance tolerance;  // 1e-6 relative

  SECTION("times and a last-digit change are not differences") {
    write_run(root / "b", 12.5 * (1 + 1e-8), 7.0, phase, "0 1.25 2.5000000001");
    const auto r = compare_output_directories(root / "a", root / "b", tolerance);
    CHECK(r.differences.empty());
    CHECK(r.files_compared == 3);
    CHECK(r.largest_relative_difference > 0);
    CHECK(r.largest_relative_difference < 1e-7);
  }
  SECTION("a result changed beyond the tolerance is named by file and place") {
    write_run(root / "b", 12.5 * (1 + 1e-4), 3.0, phase, "0 1.25 2.6");
    const auto r = compare_output_directories(root / "a", root / "b", tolerance);
    REQUIRE(r.differences.size() == 2);
    CHECK(r.differences[0].file == "mesh/deformed.vtu");
    CHECK(r.differences[0].where == "line 2 (token 4)");
    CHECK(r.differences[1].file == "summary.json");
    CHECK(r.differences[1].where == "/extension_mm");
  }
  SECTION("a changed word, a missing file and a changed record count are differences") {
    write_run(root / "b", 12.5, 3.0, "tube_material=dragon_skin_20, sheath_material=dragon_skin_30: start 1", "0 1.25 2.5");
    fs::remove(root / "b" / "mesh" / "deformed.vtu");
    auto r = compare_output_directories(root / "a", root / "b", tolerance);
    REQUIRE(r.differences.size() == 2);
    CHECK(r.differences[0].where == "record 1, column phase");
    CHECK(r.differences[1].file == "mesh/deformed.vtu");
    write(root / "b" / "history.csv", "evaluation,phase,objective,seconds\n");
    r = compare_output_directories(root / "a", root / "b", tolerance);
    CHECK(r.differences.front().where == "records");
  }
  fs::remove_all(root);
}
