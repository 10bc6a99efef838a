// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The one JSON writer of the pore tool: escaped strings, finite numbers (non-finite: null),
// separators placed by the writer, line breaks where the caller asks for them.
#ifndef TAPMC_PORES_JSON_WRITER_H
#define TAPMC_PORES_JSON_WRITER_H

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace tapmc {
namespace pores {

// Significant digits of the numbers written to the CSV and JSON outputs.
constexpr int kOutputDigits = 12;

// `v` with kOutputDigits significant digits (shortest of fixed and scientific notation).
std::string number_text(double v);

// `text` as a JSON string literal: quotes, backslashes and control characters escaped; bytes that
// are not valid UTF-8 replaced by U+FFFD, so that the output is always valid JSON.
std::string json_string(std::string_view text);

// Writes one JSON value to a stream. Containers separate their members with ", "; break_line()
// puts the next member on a new line, indented by `indent` spaces.
class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}
  JsonWriter& begin_object() { return open('{'); }
  JsonWriter& end_object() { return close('}'); }
  JsonWriter& begin_array() { return open('['); }
  JsonWriter& end_array() { return close(']'); }
  JsonWriter& key(std::string_view name);
  JsonWriter& break_line(int indent);
  JsonWriter& value(double v);  // null unless finite
  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& value(const std::string& text) { return value(std::string_view(text)); }
  JsonWriter& value(bool v);
  JsonWriter& null();
  template <typename Integer, typename = std::enable_if_t<std::is_integral_v<Integer> && !std::is_same_v<Integer, bool>>>
  JsonWriter& value(Integer v) {
    separate();
    out_ << v;
    return *this;
  }
  template <typename Range>
  JsonWriter& array(const Range& values) {
    begin_array();
    for (const auto& v : values) value(v);
    return end_array();
  }

 private:
  JsonWriter& open(char bracket);
  JsonWriter& close(char bracket);
  void separate();  // before a member: ", " unless first, or the requested line break
  std::ostream& out_;
  std::vector<bool> first_;  // per open container: no member written yet
  bool after_key_ = false;
  int break_indent_ = -1;  // >= 0: the next member starts a new line
};

}  // namespace pores
}  // namespace tapmc

#endif
