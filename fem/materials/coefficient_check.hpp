#pragma once
// Validation of law coefficients, shared by the law constructors so that a
// law built in code and a law read from JSON fail with the same message:
// the field (dotted JSON path), the value and the valid range.
#include <cstddef>
#include <string>

namespace softarm::fem {

/// "path.key", or "key" when path is empty.
std::string coefficient_field(const std::string& path, const std::string& key);

/// "field[i]".
std::string indexed_field(const std::string& field, std::size_t i);

/// Throws InputError(field, "value <value> is out of range; valid: <valid>") unless ok.
void require_coefficient(bool ok, const std::string& field, double value, const std::string& valid);

}  // namespace softarm::fem
