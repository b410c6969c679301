// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Number and token parsing shared by the readers and the stream parser (no locale, no streams).
#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace section::detail {

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

/// `s` in lower case (ASCII).
std::string lower(std::string s);

/// Parses the whole of `s` as a double ("nan"/"inf" parse, callers check finiteness).
/// A leading '+' is accepted. False when `s` is empty or has trailing characters.
inline bool parse_double(std::string_view s, double& value) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

/// Parses the whole of `s` as an integer; a leading '+' is accepted.
template <class Integer>
bool parse_integer(std::string_view s, Integer& value) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto r = std::from_chars(s.data(), s.data() + s.size(), value);
  return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
}

/// Calls `field(f)` for each field of a text row: commas separate, and so do runs of blanks;
/// a trailing comma leaves an empty last field. Stops when `field` returns false.
template <class F>
void split_fields(std::string_view line, F&& field) {
  std::size_t i = 0;
  const std::size_t len = line.size();
  const auto blank = [&](std::size_t k) { return line[k] == ' ' || line[k] == '\t'; };
  while (i < len) {
    while (i < len && blank(i)) ++i;
    const std::size_t start = i;
    while (i < len && line[i] != ',' && !blank(i)) ++i;
    const std::size_t end = i;
    while (i < len && blank(i)) ++i;
    if (i < len && line[i] == ',') {
      ++i;
      if (!field(line.substr(start, end - start))) return;
      if (i == len) field(std::string_view{});  // a trailing comma: an empty last field
      continue;
    }
    if (end > start && !field(line.substr(start, end - start))) return;
  }
}

/// The whitespace-separated words of `line` into `words` (cleared first).
void split_words(std::string_view line, std::vector<std::string_view>& words);

/// A token for an error message: at most 40 characters, control and non-ASCII bytes as \xHH,
/// so that the message stays one readable line whatever the file holds.
std::string printable(std::string_view t);
/// printable(t) in single quotes.
inline std::string quoted(std::string_view t) {
  return "'" + printable(t) + "'";
}

/// Largest coordinate magnitude the readers accept (in the file's units): beyond it squared
/// distances and 3x3 determinants overflow, so such a value is a corrupt file, not a part.
constexpr double max_coordinate = 1e15;

/// True for a section id written as a double: a whole number in [0, 2^31).
inline bool is_section_id(double value) {
  return value >= 0 && value <= 2147483647.0 && value == std::floor(value);
}

/// A section id written as a double (a whole number in [0, 2^31)) as an int; throws
/// section::Error naming `table` and its data row (0-based `row`) for any other value (a
/// table built in memory: a NaN id was written as section -2147483648).
int section_id(double value, const std::string& table, std::size_t row);

/// Drops a UTF-8 byte-order mark (some Windows editors write one); returns true if there was one.
inline bool skip_bom(std::string_view& s) {
  if (s.size() >= 3 && s.compare(0, 3, "\xEF\xBB\xBF") == 0) {
    s.remove_prefix(3);
    return true;
  }
  return false;
}

/// `t` with every byte that does not belong to a well-formed UTF-8 sequence (a stray
/// continuation byte, a cut or overlong sequence, a surrogate, beyond U+10FFFF) replaced by
/// U+FFFD: text from a stream's issue or history line bound for JSON or SVG, which must be UTF-8.
inline std::string well_formed_utf8(std::string_view t) {
  std::string out;
  out.reserve(t.size());
  for (std::size_t i = 0; i < t.size();) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned char>(t[k]); };
    const unsigned char c = b(i);
    std::size_t n = c < 0x80                 ? 1
                    : c >= 0xC2 && c <= 0xDF ? 2
                    : c >= 0xE0 && c <= 0xEF ? 3
                    : c >= 0xF0 && c <= 0xF4 ? 4
                                             : 0;
    bool ok = n > 0 && i + n <= t.size();
    for (std::size_t k = 1; ok && k < n; ++k) ok = (b(i + k) & 0xC0) == 0x80;
    if (ok && n == 3) ok = !(c == 0xE0 && b(i + 1) < 0xA0) && !(c == 0xED && b(i + 1) >= 0xA0);
    if (ok && n == 4) ok = !(c == 0xF0 && b(i + 1) < 0x90) && !(c == 0xF4 && b(i + 1) >= 0x90);
    if (ok) {
      out.append(t.substr(i, n));
      i += n;
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

/// Why the start of a text file cannot be text we read, or nullptr: UTF-16 (by its byte-order
/// mark or NUL bytes between ASCII characters), other binary data (a NUL byte), or CR-only
/// line ends (a '\r' and no '\n' in the first 64 KiB).
const char* text_encoding_problem(std::string_view head);

}  // namespace section::detail
