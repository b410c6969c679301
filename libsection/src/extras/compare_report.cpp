// SPDX-License-Identifier: GPL-3.0-or-later
// compare --report: the verdicts of a compared stream as text.
#include "section/extras/report.h"

#include "section/checks.h"
#include "section/io/stream.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/schema.h"
#include "plot_parts.h"

#include <map>
#include <string>

namespace section {

namespace {

using detail::plot::fixed;

const char* word(int verdict) {
  return verdict == 0   ? "pass"
         : verdict == 1 ? "FAIL"
         : verdict == 2 ? "not measured"
         : verdict == 3 ? "uncertain"
                        : "-";
}

// A row's value in `column`, 0 when the table has no such column (a stream compared before
// the column was written).
double at_or_0(const Table& t, std::size_t r, const char* column) {
  const long c = t.find_column(column);
  return c >= 0 ? t.at(r, static_cast<std::size_t>(c)) : 0.0;
}

// "[low, high]" of a row with columns bounds, low, high; `on` names what they bound.
std::string limits(const Table& t, std::size_t r, const std::string& prefix = "") {
  const int bounds = static_cast<int>(t.at(r, t.column(prefix.empty() ? "bounds" : prefix)));
  const std::string lo = bounds & 1 ? fixed(t.at(r, t.column("low")), 4) : "-inf";
  const std::string hi = bounds & 2 ? fixed(t.at(r, t.column("high")), 4) : "+inf";
  return "[" + lo + ", " + hi + "]";
}

std::string padded(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s + " ";
}

// The toleranced lines of one section.
std::string section_lines(int id, const Table& zones, const Table& compared) {
  static const char* const zone_items[] = {"", "_le", "_te", "_pressure", "_suction"};
  std::string out;
  const std::size_t zs = zones.column("section"), zz = zones.column("zone");
  for (std::size_t r = 0; r < zones.rows(); ++r) {
    if (static_cast<int>(zones.at(r, zs)) != id) continue;
    const std::string z = zone_items[static_cast<int>(zones.at(r, zz))];
    const int v = static_cast<int>(zones.at(r, zones.column("verdict")));
    if (v >= 0)
      out += "  " + padded("profile" + z, 20) +
             padded("deviations " + fixed(zones.at(r, zones.column("min")), 4) + " .. " +
                        fixed(zones.at(r, zones.column("max")), 4),
                    56) +
             padded(limits(zones, r), 27) + word(v) + "\n";
    const int fv = static_cast<int>(zones.at(r, zones.column("form_verdict")));
    if (fv >= 0)
      out +=
          "  " + padded("form" + z, 20) + padded("form " + fixed(zones.at(r, zones.column("form")), 4), 56) +
          padded("[-inf, " + fixed(zones.at(r, zones.column("form_limit")), 4) + "]", 27) + word(fv) + "\n";
  }
  const auto& items = compared_items();
  const std::size_t cs = compared.column("section"), ci = compared.column("item");
  for (std::size_t r = 0; r < compared.rows(); ++r) {
    if (static_cast<int>(compared.at(r, cs)) != id) continue;
    const int v = static_cast<int>(compared.at(r, compared.column("verdict")));
    if (v < 0) continue;
    const bool on_value = compared.at(r, compared.column("on_value")) != 0;
    const double u = at_or_0(compared, r, "uncertainty");
    std::string what = compared.at(r, compared.column("measured")) == 0
                           ? std::string("not measured")
                           : "value " + fixed(compared.at(r, compared.column("value")), 4) + " nominal " +
                                 fixed(compared.at(r, compared.column("nominal")), 4) + " deviation " +
                                 fixed(compared.at(r, compared.column("deviation")), 4);
    if (u > 0) what += " +- " + fixed(u, 4);
    // Why a value is uncertain: the checks camber flagged it (or the nominal's) by.
    const std::string flags = check_names_text(flags_mask(at_or_0(compared, r, "flags")), ","),
                      nominal_flags =
                          check_names_text(flags_mask(at_or_0(compared, r, "nominal_flags")), ",");
    std::string why;
    if (!flags.empty()) why += " (flagged: " + flags + ")";
    if (!nominal_flags.empty()) why += " (nominal flagged: " + nominal_flags + ")";
    out += "  " + padded(items.at(static_cast<std::size_t>(compared.at(r, ci))), 20) + padded(what, 56) +
           padded(limits(compared, r) + (on_value ? " on value" : ""), 27) + word(v) + why + "\n";
  }
  return out;
}

}  // namespace

std::string compare_report(const Stream& stream) {
  const Table& verdicts = schema::verdicts.get(stream);
  const Table* zones = schema::zones.find(stream);
  const Table* compared = schema::compared.find(stream);
  int passed = 0, failed = 0, not_measured = 0, uncertain = 0;
  std::string body;
  for (std::size_t r = 0; r < verdicts.rows(); ++r) {
    const int id = static_cast<int>(verdicts.at(r, verdicts.column("section")));
    const int v = static_cast<int>(verdicts.at(r, verdicts.column("verdict")));
    const int p = static_cast<int>(verdicts.at(r, verdicts.column("passed")));
    const int f = static_cast<int>(verdicts.at(r, verdicts.column("failed")));
    const int n = static_cast<int>(verdicts.at(r, verdicts.column("not_measured")));
    const int u = static_cast<int>(at_or_0(verdicts, r, "uncertain"));
    passed += p;
    failed += f;
    not_measured += n;
    uncertain += u;
    body += "section " + std::to_string(id) + ": " + (v < 0 ? std::string("nothing toleranced") : word(v)) +
            " (" + std::to_string(p) + " passed, " + std::to_string(f) + " failed, " + std::to_string(n) +
            " not measured, " + std::to_string(u) + " uncertain)\n";
    if (zones && compared) body += section_lines(id, *zones, *compared);
  }
  const std::string verdict = failed         ? "FAIL"
                              : not_measured ? "NOT MEASURED"
                              : uncertain    ? "UNCERTAIN"
                              : passed       ? "PASS"
                                             : "nothing toleranced";
  return "blade: " + verdict + " (" + std::to_string(passed) + " passed, " + std::to_string(failed) +
         " failed, " + std::to_string(not_measured) + " not measured, " + std::to_string(uncertain) +
         " uncertain, over " + std::to_string(verdicts.rows()) + " sections)\n" + body;
}

}  // namespace section
