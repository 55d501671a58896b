#pragma once
// Uniaxial tension test data for material fitting (thesis Ch. 3: the Dragon
// Skin laws were least-squares fits to ASTM D638 uniaxial tests).
//
// CSV format: a header line `stretch,nominal_stress_MPa`, then one row per
// point: stretch λ (> 0, strictly increasing) and nominal (1st Piola-Kirchhoff,
// force per reference area) stress in MPa. Blank lines and lines starting
// with '#' are ignored; at least 3 rows.
#include <string>
#include <vector>

namespace softarm::fem {

struct UniaxialData {
  std::vector<double> stretch;
  std::vector<double> nominal_stress_MPa;
  std::string source;  // the file it was read from
};

/// Reads and validates a CSV as above. Any defect raises InputError whose
/// field is the file name and whose message names the line and the value.
UniaxialData read_uniaxial_csv(const std::string& file_name);

/// Parses CSV text; `file_name` only labels the errors.
UniaxialData parse_uniaxial_csv(const std::string& text, const std::string& file_name);

}  // namespace softarm::fem
