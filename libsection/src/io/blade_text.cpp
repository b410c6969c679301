// SPDX-License-Identifier: GPL-3.0-or-later
// The whole blade as a table for people (blade_text.h).
#include "section/io/blade_text.h"

#include <charconv>
#include <cmath>
#include <string>

namespace section {

namespace {

// `value` with `decimals` digits, "-" when not finite, never "-0.000".
std::string number(double value, int decimals) {
  if (!std::isfinite(value)) return "-";
  char buf[400];  // room for the largest double in fixed notation (309 digits) and its decimals
  const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, decimals);
  if (r.ec != std::errc()) return "?";  // never the buffer's bytes
  std::string text(buf, r.ptr);
  if (text[0] == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

// number() right-aligned in `width` columns, then '!' when flagged (else a blank).
std::string cell(double value, int decimals, std::size_t width, bool flagged) {
  std::string text = number(value, decimals);
  // Right-aligned, and a blank before a number as wide as its column (a span of 20138 mm ran into
  // the section id).
  text.insert(0, text.size() < width ? width - text.size() : 1, ' ');
  return text + (flagged ? "!" : " ");
}

std::string vector_text(const Eigen::Vector3d& d) {
  return "(" + number(d.x(), 3) + ", " + number(d.y(), 3) + ", " + number(d.z(), 3) + ")";
}

}  // namespace

std::string format_blade_text(const StackingResult& b, const std::string& units) {
  std::string out = "blade of " + std::to_string(b.sections.size()) + " sections, hub to tip: lengths in " +
                    units + " (4 decimals), angles in degrees (3); reference section " +
                    std::to_string(b.reference) + "; '!' after a value flagged by the checks named last\n";
  out += "axial " + vector_text(b.axial) + "  tangential " + vector_text(b.tangential) + "  span " +
         vector_text(b.span_direction) + "\n\n";
  out +=
      "section       span  fraction   stagger     twist       lean      sweep        bow  axial_bow      "
      "chord "
      " thickness  flags\n";
  for (const StackedValues& v : b.sections) {
    const auto is = [&](StackCheck c, const char* column) {
      for (const auto& n : stack_check_names)
        if (n.check == c && (v.flags & static_cast<std::uint32_t>(c))) {
          const std::string list = std::string(" ") + n.columns + " ";
          if (list.find(std::string(" ") + column + " ") != std::string::npos) return true;
        }
      return false;
    };
    const auto any = [&](const char* column) {
      for (const auto& n : stack_check_names)
        if (is(n.check, column)) return true;
      return false;
    };
    std::string id = std::to_string(v.id) + (v.reference ? "*" : "");
    out += std::string(id.size() < 7 ? 7 - id.size() : 0, ' ') + id;
    out += cell(v.span, 4, 10, any("span")) + cell(v.fraction, 3, 9, any("span"));
    out += cell(v.stagger, 3, 9, any("stagger")) + cell(v.twist, 3, 9, any("twist"));
    out += cell(v.lean, 4, 10, any("lean")) + cell(v.sweep, 4, 10, any("sweep"));
    out += cell(v.bow, 4, 10, any("bow")) + cell(v.axial_bow, 4, 10, any("axial_bow"));
    out += cell(v.chord, 4, 10, any("chord")) + cell(v.max_thickness, 4, 10, any("max_thickness"));
    std::string names;
    for (const auto& n : stack_check_names)
      if (v.flags & static_cast<std::uint32_t>(n.check))
        names += (names.empty() ? "" : ",") + std::string(n.name);
    out += " " + (names.empty() ? std::string("none") : names) + "\n";
  }
  out += "\n* the reference section (twist, lean and sweep 0)\n";
  return out;
}

}  // namespace section
