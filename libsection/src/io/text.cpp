// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/text.h"

#include "section/error.h"

#include <cctype>
#include <cstdio>

namespace section::detail {

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

void split_words(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  for (std::size_t i = 0; i < line.size();) {
    if (is_space(line[i])) {
      ++i;
      continue;
    }
    const std::size_t s = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    words.push_back(line.substr(s, i - s));
  }
}

std::string printable(std::string_view t) {
  std::string q;
  for (std::size_t i = 0; i < t.size() && i < 40; ++i) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    if (c >= 0x20 && c < 0x7f) {
      q += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      q += hex;
    }
  }
  return t.size() > 40 ? q + "..." : q;
}

const char* text_encoding_problem(std::string_view head) {
  if (head.size() >= 2 &&
      ((head[0] == '\xFF' && head[1] == '\xFE') || (head[0] == '\xFE' && head[1] == '\xFF')))
    return "UTF-16 text (save it as UTF-8 or ASCII)";
  head = head.substr(0, 1 << 16);
  const auto nul = head.find('\0');
  if (nul == std::string_view::npos) {
    // Line ends of classic Mac OS: one endless line to every reader.
    const auto cr = head.find('\r');
    if (cr != std::string_view::npos && cr + 1 < head.size() && head.find('\n') == std::string_view::npos)
      return "CR-only line ends (classic Mac OS; convert them to LF)";
    return nullptr;
  }
  const bool le = head.size() >= 4 && head[1] == '\0' && head[3] == '\0' && head[0] && head[2];
  const bool be = head.size() >= 4 && head[0] == '\0' && head[2] == '\0' && head[1] && head[3];
  if (le || be) return "UTF-16 text (save it as UTF-8 or ASCII)";
  return "binary data in a text file";
}

int section_id(double value, const std::string& table, std::size_t row) {
  if (is_section_id(value)) return static_cast<int>(value);
  char number[32];
  std::snprintf(number, sizeof number, "%g", value);
  throw Error("pipe: table '" + table + "' data row " + std::to_string(row + 1) + ": section " + number +
              " is not a section id (a whole number of 0 or more)");
}

}  // namespace section::detail
