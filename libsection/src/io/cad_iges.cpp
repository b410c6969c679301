// SPDX-License-Identifier: GPL-3.0-or-later
// The sections' curves as an IGES 5.3 file (US PRO/IPO-100, fixed 80-column ASCII):
// Start, Global, Directory Entry, Parameter Data and Terminate sections, one entity 126
// (rational B-spline curve) per curve.
#include "section/io/cad.h"

#include "io/cad_common.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace section {

namespace {

// An 80-column line: `data` left-justified in 72 columns, then the section letter and the
// sequence number in columns 73-80.
std::string line(const std::string& data, char letter, int sequence) {
  char tail[16];
  std::snprintf(tail, sizeof tail, "%c%7d\n", letter, sequence);
  std::string out = data;
  out.resize(72, ' ');
  return out + tail;
}

// A string as IGES writes it (Hollerith: its length, H, the characters).
std::string hollerith(const std::string& s) {
  return std::to_string(s.size()) + "H" + s;
}

// Free-format parameters packed into lines of at most `width` columns without splitting
// one, separated by commas and closed by a semicolon.
std::vector<std::string> pack(const std::vector<std::string>& tokens, std::size_t width) {
  std::vector<std::string> out(1);
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string t = tokens[i] + (i + 1 < tokens.size() ? "," : ";");
    if (out.back().size() + t.size() > width && !out.back().empty()) out.emplace_back();
    out.back() += t;
  }
  return out;
}

// A name for the header: printable ASCII, at most 40 characters (the last ones of a path).
std::string header_name(const std::string& s) {
  std::string out;
  for (char c : s) out += (c >= 32 && c < 127) ? c : '_';
  return out.size() > 40 ? out.substr(out.size() - 40) : out;
}

// The parameters of an entity 126 for one curve (IGES 5.3, section 4.23).
std::vector<std::string> curve_parameters(const CadCurve& c) {
  const detail::CadSpline s = detail::cad_spline(c);
  const std::size_t k = s.control.size() - 1;
  std::vector<std::string> p = {"126", std::to_string(k),    std::to_string(s.degree),
                                "1",   s.closed ? "1" : "0", "1",
                                "0"};  // planar, closed, polynomial (weights all 1), not periodic
  for (double t : s.knots) p.push_back(detail::cad_real(t, 'D'));
  for (std::size_t i = 0; i <= k; ++i) p.push_back("1.0");
  for (const auto& q : s.control)
    for (int a = 0; a < 3; ++a) p.push_back(detail::cad_real(q[a], 'D'));
  p.push_back(detail::cad_real(s.knots[static_cast<std::size_t>(s.degree)], 'D'));
  p.push_back(detail::cad_real(s.knots[s.control.size()], 'D'));
  for (int a = 0; a < 3; ++a) p.push_back(detail::cad_real(c.frame.n[a], 'D'));
  return p;
}

std::vector<std::string> global_parameters(const std::vector<CadCurve>& curves, const CadOptions& o) {
  const detail::CadUnit& unit = detail::cad_unit(o.units);
  double extent = 0;
  for (const auto& c : curves)
    for (const auto& q : detail::cad_spline(c).control) extent = std::max(extent, q.cwiseAbs().maxCoeff());
  const std::string stamp = hollerith(o.timestamp);
  return {"1H,",
          "1H;",
          hollerith("libsection sections"),
          hollerith(header_name(o.source)),
          hollerith("libsection"),
          hollerith("libsection tocad"),
          "32",
          "38",
          "6",
          "308",
          "15",
          hollerith("libsection sections"),
          "1.0",
          std::to_string(unit.iges),
          hollerith(unit.iges_name),
          "1",
          "1.0",
          stamp,
          "1.0D-4",
          detail::cad_real(extent, 'D'),
          "",
          "",
          "11",
          "0",
          stamp};
}

// Directory entry fields (8 columns each, right-justified) into one 72-column line.
std::string fields(const std::vector<std::string>& f) {
  std::string out;
  for (const auto& s : f) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%8s", s.c_str());
    out += buf;
  }
  return out;
}

}  // namespace

std::string format_iges(const std::vector<CadCurve>& curves, const CadOptions& options) {
  std::string start_section, global_section, directory, parameters;
  int s = 0, g = 0, d = 0, p = 0;
  start_section += line("libsection: blade section curves (B-splines)", 'S', ++s);
  if (!options.source.empty()) start_section += line("from " + header_name(options.source), 'S', ++s);
  for (const auto& text : pack(global_parameters(curves, options), 72))
    global_section += line(text, 'G', ++g);
  for (const auto& c : curves) {
    const int entry = d + 1, first = p + 1;
    const auto lines = pack(curve_parameters(c), 64);
    for (const auto& text : lines) {
      char pointer[16];
      std::snprintf(pointer, sizeof pointer, " %7d", entry);
      parameters += line(text + std::string(64 - text.size(), ' ') + pointer, 'P', ++p);
    }
    const std::string label = "S" + std::to_string(c.section) + "L" + std::to_string(c.loop);
    directory +=
        line(fields({"126", std::to_string(first), "0", "1", "0", "0", "0", "0", "00000000"}), 'D', ++d);
    directory += line(fields({"126", "0", "0", std::to_string(lines.size()), "0", "", "",
                              label.size() <= 8 ? label : label.substr(0, 8), std::to_string(c.section)}),
                      'D', ++d);
  }
  char counts[64];
  std::snprintf(counts, sizeof counts, "S%7dG%7dD%7dP%7d", s, g, d, p);
  return start_section + global_section + directory + parameters + line(counts, 'T', 1);
}

}  // namespace section
