// SPDX-License-Identifier: GPL-3.0-or-later
// The params table as text for people: aligned blocks, chosen digits, words for codes.
#include "section/io/params_text.h"

#include "section/checks.h"
#include "section/edge.h"
#include "section/error.h"
#include "section/units.h"
#include "io/text.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace section {

namespace {

constexpr double none = std::numeric_limits<double>::quiet_NaN();

// `value` printed with `decimals` digits after the point, or "-" when it is not finite.
std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

// `text` padded with spaces to `width` (on the left when `right`).
std::string pad(const std::string& text, std::size_t width, bool right = false) {
  if (text.size() >= width) return text;
  const std::string fill(width - text.size(), ' ');
  return right ? fill + text : text + fill;
}

// One row of a table by column name; a column the table lacks reads as NaN.
struct RowView {
  const Table* table = nullptr;
  long row = -1;
  double operator()(const char* column) const {
    if (!table || row < 0) return none;
    const long c = table->find_column(column);
    return c < 0 ? none : table->at(std::size_t(row), std::size_t(c));
  }
};

// The row of `table` (may be null) for section `s`: its first row with that id.
RowView row_of(const Table* table, int s) {
  RowView view{table, -1};
  if (!table) return view;
  const long c = table->find_column("section");
  if (c < 0) return view;
  for (std::size_t r = 0; r < table->rows(); ++r)
    if (table->at(r, std::size_t(c)) == s) {
      view.row = long(r);
      break;
    }
  return view;
}

// A cell of a block: label, value right-aligned, then its unit or words, and '!' when a
// failed check flags the value.
std::string cell(const std::string& label, const std::string& value, const std::string& after,
                 bool flagged = false) {
  return pad(label, 15) + pad(value, 11, true) + " " + pad(after + (flagged ? "!" : ""), 11);
}

std::string shape_word(double code) {
  if (!std::isfinite(code)) return "";
  return edge_shape_name(static_cast<EdgeShape>(int(code)));
}

std::string side_word(double code) {
  return code > 0 ? "left" : code < 0 ? "right" : "-";
}

// The checks of a flags mask by name, ", "-separated; "none" for 0.
std::string check_words(double flags) {
  if (!std::isfinite(flags)) return "-";
  const std::string out = check_names_text(flags_mask(flags));
  return out.empty() ? "none" : out;
}

// `text` cut to `width` columns with "..." at the end when longer.
std::string shorten(const std::string& text, std::size_t width) {
  if (text.size() <= width) return text;
  return width > 3 ? text.substr(0, width - 3) + "..." : text.substr(0, width);
}

// `label` then `text` wrapped at ", " to `width` columns, continuation lines indented.
std::string wrapped(const std::string& label, const std::string& text, std::size_t width) {
  const std::string indent = "  " + pad("", 15);
  std::string out = "  " + pad(label, 15), line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(", ", start);
    const std::string word =
        text.substr(start, end == std::string::npos ? std::string::npos : end - start + 1);
    if (!line.empty() && indent.size() + line.size() + 1 + word.size() > width) {
      out += line + "\n" + indent;
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    start = end == std::string::npos ? text.size() : end + 2;
  }
  return out + line + "\n";
}

// The plane line of a section: its offset along its normal, from the frames table.
std::string plane_line(const RowView& frame, double mm) {
  const double nx = frame("n_x"), ny = frame("n_y"), nz = frame("n_z");
  const double offset = frame("origin_x") * nx + frame("origin_y") * ny + frame("origin_z") * nz;
  if (!std::isfinite(offset)) return "";
  return "   plane " + fixed(offset * mm, 4) + " mm along n (" + fixed(nx, 3) + ", " + fixed(ny, 3) + ", " +
         fixed(nz, 3) + ")";
}

// The value rows of one section's params, each value a failed check flags marked.
std::string value_rows(const RowView& p, double mm) {
  const CheckBits flags = flags_mask(p("flags"));  // 0 for a missing or non-finite cell
  const auto flagged = [&](const char* c) { return checks_flagging(flags, c) != 0; };
  const auto length = [&](const char* label, const char* c, const std::string& after = "mm") {
    return cell(label, fixed(p(c) * mm, 4), after, flagged(c));
  };
  const auto angle = [&](const char* label, const char* c) {
    return cell(label, fixed(p(c), 3), "deg", flagged(c));
  };
  std::string out;
  auto row = [&](const std::string& a, const std::string& b, const std::string& c) {
    std::string line = "  " + a + " " + b + " " + c;
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  };
  row(length("chord", "chord"), length("caliper chord", "caliper_chord"),
      length("camber length", "camber_length"));
  row(length("max thickness", "max_thickness"),
      cell("at", fixed(p("max_thickness_pos"), 3), "of camber", flagged("max_thickness_pos")),
      cell("pressure side", side_word(p("pressure_side")), "", flagged("pressure_side")));
  row(length("LE radius", "le_radius", "mm " + shape_word(p("le_shape"))),
      length("TE radius", "te_radius", "mm " + shape_word(p("te_shape"))),
      cell("area", fixed(p("area") * mm * mm, 4), "mm^2", flagged("area")));
  row(angle("stagger", "stagger"), angle("inlet angle", "inlet_angle"),
      angle("outlet angle", "outlet_angle"));
  row(angle("camber angle", "camber_angle"), angle("caliper stagger", "caliper_stagger"), "");
  return out;
}

// The values' standard errors camber gives (its `..._sigma` columns), ", "-separated: each
// where it is known (over 0); "" when none is (the noise unknown, or a stream without them).
std::string sigma_words(const RowView& p, double mm) {
  const struct {
    const char *label, *column;
    bool angle;
  } values[] = {{"chord", "chord_sigma", false},
                {"max thickness", "max_thickness_sigma", false},
                {"LE radius", "le_radius_sigma", false},
                {"TE radius", "te_radius_sigma", false},
                {"inlet angle", "inlet_angle_sigma", true},
                {"outlet angle", "outlet_angle_sigma", true}};
  std::string out;
  for (const auto& v : values) {
    const double sigma = p(v.column);
    if (!(sigma > 0) || !std::isfinite(sigma)) continue;
    out += (out.empty() ? "" : ", ") + std::string(v.label) + " " +
           (v.angle ? fixed(sigma, 3) + " deg" : fixed(sigma * mm, 4) + " mm");
  }
  return out;
}

// A hollow blade's cavities in section s (the walls table's rows), two lines each: its
// thinnest wall, marked when a failed check flags it, and its area; then its thinnest to each
// side.
std::string wall_rows(const Table* walls, int s, double mm) {
  if (!walls) return "";
  const long c = walls->find_column("section");
  if (c < 0) return "";
  std::string out;
  const auto add = [&](std::string line, CheckBits flags) {
    if (flags) line += " " + check_names_text(flags);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  };
  for (std::size_t r = 0; r < walls->rows(); ++r) {
    if (walls->at(r, std::size_t(c)) != s) continue;
    const RowView w{walls, long(r)};
    const CheckBits flags = checks_flagging(flags_mask(w("flags")), "wall");
    add("  " + pad("cavity " + fixed(w("loop"), 0), 15) +
            cell("wall", fixed(w("wall") * mm, 4), "mm", flags) + " " +
            cell("area", fixed(w("area") * mm * mm, 4), "mm^2"),
        flags);
    if (!std::isfinite(w("pressure_wall"))) continue;  // a stream written without the sides' walls
    const CheckBits pressure = checks_flagging(flags_mask(w("pressure_flags")), "wall"),
                    suction = checks_flagging(flags_mask(w("suction_flags")), "wall");
    add("  " + pad("", 15) + cell("to pressure", fixed(w("pressure_wall") * mm, 4), "mm", pressure) + " " +
            cell("to suction", fixed(w("suction_wall") * mm, 4), "mm", suction),
        pressure | suction);
  }
  return out;
}

}  // namespace

std::string format_params_text(const Stream& stream, const ParamsTextOptions& options) {
  const Table& params = stream.get("params", "camber");
  const Table* frames = stream.find("frames");
  const Table* walls = stream.find("walls");
  const double mm = mm_per_unit(stream.units);
  const std::size_t width = std::size_t(options.width > 40 ? options.width : 40);
  std::set<int> sections;
  const long sc = params.find_column("section");
  if (sc < 0) throw Error("params: the table has no 'section' column");
  for (std::size_t r = 0; r < params.rows(); ++r)
    sections.insert(detail::section_id(params.at(r, std::size_t(sc)), params.name, r));
  std::map<int, std::vector<std::string>> issues;
  for (const auto& i : stream.issues)
    if (i.section >= 0) {
      sections.insert(i.section);
      issues[i.section].push_back(i.stage + ": " + i.message);
    }
  std::string out =
      "params of " + std::to_string(sections.size()) +
      " sections: lengths in mm (to 0.1 um), angles in degrees, 'at': along the camber line, "
      "LE 0, TE 1\n'!' after a value's unit: a failed check flags the value (the section's "
      "failed checks name them)\n'std. error': the values' standard errors through the points' noise, where "
      "known\n";
  for (const int s : sections) {
    const RowView p = row_of(&params, s);
    out += "\nsection " + std::to_string(s) + plane_line(row_of(frames, s), mm) +
           (p.row < 0 ? "   (no params)" : "") + "\n";
    if (p.row >= 0) {
      out += value_rows(p, mm);
      out += wall_rows(walls, s, mm);
      if (const std::string sigmas = sigma_words(p, mm); !sigmas.empty())
        out += wrapped("std. error", sigmas, width);
      out += wrapped("failed checks", check_words(p("flags")), width);
    }
    const auto& list = issues[s];
    for (std::size_t k = 0; k < list.size() && int(k) < options.max_issues; ++k)
      out += "  " + pad("issue", 15) + shorten(list[k], width - 17) + "\n";
    if (int(list.size()) > options.max_issues)
      out += "  " + pad("", 15) + "(" + std::to_string(list.size() - std::size_t(options.max_issues)) +
             " more issues in the stream)\n";
  }
  return out;
}

}  // namespace section
