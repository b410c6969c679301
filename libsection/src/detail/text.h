#pragma once
// Number and token parsing shared by the readers and the pipe parser (no locale, no streams).
#include <charconv>
#include <string_view>

namespace section::detail {

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

/// Parses the whole of `s` as a double ("nan"/"inf" parse, callers check finiteness).
/// A leading '+' is accepted. False when `s` is empty or has trailing characters.
inline bool parse_double(std::string_view s, double& value) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

/// Largest coordinate magnitude the readers accept (in the file's units): beyond it squared
/// distances and 3x3 determinants overflow, so such a value is a corrupt file, not a part.
constexpr double max_coordinate = 1e15;

/// Drops a UTF-8 byte-order mark (some Windows editors write one); returns true if there was one.
inline bool skip_bom(std::string_view& s) {
  if (s.size() >= 3 && s.compare(0, 3, "\xEF\xBB\xBF") == 0) {
    s.remove_prefix(3);
    return true;
  }
  return false;
}

/// Why the start of a text file cannot be text we read, or nullptr: UTF-16 (by its byte-order
/// mark or NUL bytes between ASCII characters) or other binary data (a NUL byte).
inline const char* text_encoding_problem(std::string_view head) {
  if (head.size() >= 2 && ((head[0] == '\xFF' && head[1] == '\xFE') || (head[0] == '\xFE' && head[1] == '\xFF')))
    return "UTF-16 text (save it as UTF-8 or ASCII)";
  head = head.substr(0, 1 << 16);
  const auto nul = head.find('\0');
  if (nul == std::string_view::npos) return nullptr;
  const bool le = head.size() >= 4 && head[1] == '\0' && head[3] == '\0' && head[0] && head[2];
  const bool be = head.size() >= 4 && head[0] == '\0' && head[2] == '\0' && head[1] && head[3];
  if (le || be) return "UTF-16 text (save it as UTF-8 or ASCII)";
  return "binary data in a text file";
}

}  // namespace section::detail
