#pragma once
// The one exception type for bad input. Its message always names the JSON
// field (as a dotted path), the offending value and what would be valid, so a
// user can fix the file without reading code. The CLI turns it into exit 2.
#include <stdexcept>
#include <string>

namespace softarm::fem {

class InputError : public std::runtime_error {
 public:
  InputError(std::string field, const std::string& message)
      : std::runtime_error("input error: " + (field.empty() ? std::string() : "'" + field + "': ") + message),
        field_(std::move(field)), message_(message) {}
  const std::string& field() const { return field_; }
  /// The message without the "input error: 'field': " prefix (to re-raise it under another field).
  const std::string& message() const { return message_; }

 private:
  std::string field_, message_;
};

}  // namespace softarm::fem
