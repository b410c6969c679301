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

}  // namespace section::detail
