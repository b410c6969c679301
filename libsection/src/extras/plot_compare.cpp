// SPDX-License-Identifier: GPL-3.0-or-later
// compare's layer of the plots: whiskers (each measured point's deviation along the
// nominal's normal, magnified, coloured by the share of its zone's tolerance it uses), the
// zones' tolerance bands, and the verdicts of the section and of the blade.
#include "plot_parts.h"

#include "section/io/stream.h"
#include "section/pipe/compare_stream.h"

#include <algorithm>
#include <cmath>

namespace section::detail::plot {

namespace {

const char* const zone_names[] = {"whole", "LE", "TE", "pressure side", "suction side"};

// The whiskers' magnification: the largest deviation or tolerance limit drawn 4 % of the
// profile's extent long, rounded down to 1, 2 or 5 times a power of ten.
double magnification(const SectionData& d) {
  Box box;
  double largest = 0;
  for (const Whisker& w : d.whiskers) {
    box.add(w.foot);
    if (!w.outlier) largest = std::max(largest, std::abs(w.deviation));
  }
  for (const auto& [zone, b] : d.bands) largest = std::max({largest, std::abs(b.low), std::abs(b.high)});
  if (box.empty() || !(largest > 0)) return 1;
  const double target = 0.04 * std::max(box.u1 - box.u0, box.v1 - box.v0) / largest;
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  return target >= 5 * p ? 5 * p : target >= 2 * p ? 2 * p : p;
}

// The whisker's colour: green within half its zone's tolerance, amber within it, red
// beyond, grey without a tolerance.
const char* colour(const SectionData& d, const Whisker& w) {
  const auto b = d.bands.find(w.zone);
  const auto whole = d.bands.find(0);
  const ZoneBand* band = b != d.bands.end() && b->second.bounds           ? &b->second
                         : whole != d.bands.end() && whole->second.bounds ? &whole->second
                                                                          : nullptr;
  if (!band || w.outlier) return "#999999";
  const bool up = w.deviation >= 0;
  if (!(band->bounds & (up ? 2 : 1))) return "#999999";
  const double limit = up ? band->high : band->low;
  const double use = limit != 0 ? w.deviation / limit : (w.deviation == 0 ? 0.0 : 2.0);
  return use > 1 ? "#d62728" : use > 0.5 ? "#e6a100" : "#2ca02c";
}

std::string point(const View& v, const V2& p) {
  return px(v.x(p.x())) + "," + px(v.y(p.y()));
}

}  // namespace

void collect_compare(const Stream& stream, int section, SectionData& d) {
  for (const auto& r : rows_of(stream, "deviations", section,
                               {"foot_u", "foot_v", "nu", "nv", "deviation", "zone", "outlier"})) {
    Whisker w{{r[0], r[1]}, {r[2], r[3]}, r[4], static_cast<int>(r[5]), r[6] == 1};
    if (finite(w.foot) && finite(w.normal) && std::isfinite(w.deviation)) d.whiskers.push_back(w);
  }
  for (const auto& r : rows_of(stream, "zones", section, {"zone", "bounds", "low", "high", "verdict"}))
    d.bands[static_cast<int>(r[0])] = {static_cast<int>(r[1]), r[2], r[3], static_cast<int>(r[4])};
  for (const auto& r :
       rows_of(stream, "verdicts", section, {"verdict", "passed", "failed", "not_measured", "uncertain"})) {
    d.verdict = static_cast<int>(r[0]);
    d.passed = static_cast<int>(r[1]);
    d.failed = static_cast<int>(r[2]);
    d.not_measured = static_cast<int>(r[3]);
    d.uncertain = std::isfinite(r[4]) ? static_cast<int>(r[4]) : 0;  // NaN: compared before it was counted
  }
  for (const auto& r : rows_of(stream, "zones", section, {"zone", "verdict", "form_verdict"}))
    for (const auto& [v, what] : {std::pair{r[1], "profile"}, std::pair{r[2], "form"}}) {
      const std::string name = std::string(what) + " " + zone_names[static_cast<int>(r[0]) % 5];
      if (v == 1) d.failed_items.push_back(name);
      if (v == 2) d.unmeasured_items.push_back(name);
    }
  const auto& items = compared_items();
  for (const auto& r : rows_of(stream, "compared", section, {"item", "verdict"})) {
    const std::size_t k = static_cast<std::size_t>(r[0]);
    if (k >= items.size()) continue;
    if (r[1] == 1) d.failed_items.push_back(items[k]);
    if (r[1] == 2) d.unmeasured_items.push_back(items[k]);
    if (r[1] == 3) d.uncertain_items.push_back(items[k]);
  }
}

void draw_compare(std::string& s, const SectionData& d, const View& v) {
  if (d.whiskers.empty()) return;
  const double m = magnification(d);
  // The band of each zone (its own, else the whole profile's) along its points; a jump
  // between consecutive points (the zone running past the loop's start) starts a new run.
  std::vector<double> steps;
  for (std::size_t i = 1; i < d.whiskers.size(); ++i)
    steps.push_back((d.whiskers[i].foot - d.whiskers[i - 1].foot).norm());
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const double jump = 20 * (steps.empty() ? 0.0 : steps[steps.size() / 2]);
  s += "<g class=\"tolerance-bands\" data-magnification=\"" + trimmed(m, 6) + "\">";
  for (int zone = 1; zone < 5; ++zone) {
    const auto own = d.bands.find(zone), whole = d.bands.find(0);
    const ZoneBand* band = own != d.bands.end() && own->second.bounds       ? &own->second
                           : whole != d.bands.end() && whole->second.bounds ? &whole->second
                                                                            : nullptr;
    if (!band) continue;
    for (int side : {1, 2}) {
      if (!(band->bounds & side)) continue;
      const double limit = side == 1 ? band->low : band->high;
      std::string path;
      const Whisker* last = nullptr;
      for (const Whisker& w : d.whiskers) {
        if (w.zone != zone) continue;
        const bool start = !last || (w.foot - last->foot).norm() > jump;
        path += (start ? " M" : " L") + point(v, w.foot + m * limit * w.normal);
        last = &w;
      }
      if (!path.empty())
        s += "<path class=\"tolerance-band\" fill=\"none\" stroke=\"#888\" stroke-width=\"0.8\" "
             "stroke-dasharray=\"4 3\" d=\"" +
             path.substr(1) + "\"/>";
    }
  }
  s += "</g><g class=\"whiskers\" data-magnification=\"" + trimmed(m, 6) + "\">";
  for (const Whisker& w : d.whiskers)
    s += "<line stroke=\"" + std::string(colour(d, w)) + "\" stroke-width=\"1\" x1=\"" + px(v.x(w.foot.x())) +
         "\" y1=\"" + px(v.y(w.foot.y())) + "\" x2=\"" +
         px(v.x(w.foot.x() + m * w.deviation * w.normal.x())) + "\" y2=\"" +
         px(v.y(w.foot.y() + m * w.deviation * w.normal.y())) + "\"/>";
  s += "</g>";
}

std::string verdict_line(const SectionData& d) {
  if (d.verdict == -2) return "";
  std::string line = d.verdict == 1   ? "FAIL"
                     : d.verdict == 2 ? "NOT MEASURED"
                     : d.verdict == 3 ? "UNCERTAIN"
                     : d.verdict == 0 ? "PASS"
                                      : "nothing toleranced";
  line += " (" + std::to_string(d.passed) + " passed, " + std::to_string(d.failed) + " failed, " +
          std::to_string(d.not_measured) + " not measured, " + std::to_string(d.uncertain) + " uncertain)";
  auto list = [](const std::vector<std::string>& v) {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
    return out;
  };
  if (!d.failed_items.empty()) line += "; failed: " + list(d.failed_items);
  if (!d.unmeasured_items.empty()) line += "; not measured: " + list(d.unmeasured_items);
  if (!d.uncertain_items.empty()) line += "; uncertain: " + list(d.uncertain_items);
  return line;
}

std::string whisker_legend(const SectionData& d) {
  if (d.whiskers.empty()) return "";
  return "whiskers: deviations along the nominal's normal x" + trimmed(magnification(d), 6) +
         " (green within half the zone's tolerance, amber within it, red beyond, grey none); dashed: the "
         "tolerance band";
}

std::string blade_verdict_html(const std::vector<SectionData>& data) {
  int compared = 0, passed = 0, failed = 0, not_measured = 0, uncertain = 0;
  std::string failing;
  for (const auto& d : data) {
    if (d.verdict == -2) continue;
    ++compared;
    passed += d.passed;
    failed += d.failed;
    not_measured += d.not_measured;
    uncertain += d.uncertain;
    if (d.verdict == 1) failing += (failing.empty() ? "" : ", ") + std::to_string(d.id);
  }
  if (!compared) return "";
  const std::string verdict = failed         ? "FAIL"
                              : not_measured ? "NOT MEASURED"
                              : uncertain    ? "UNCERTAIN"
                              : passed       ? "PASS"
                                             : "nothing toleranced";
  const std::string colour = failed ? "#c00" : not_measured || uncertain ? "#b07800" : "#080";
  return "<p class=\"verdict\" style=\"font-size:22px;font-weight:bold;color:" + colour +
         "\">Blade: " + verdict + "</p>\n<p>" + std::to_string(passed) + " values passed, " +
         std::to_string(failed) + " failed, " + std::to_string(not_measured) + " not measured, " +
         std::to_string(uncertain) + " uncertain, over " + std::to_string(compared) + " sections" +
         (failing.empty() ? "" : "; failing sections: " + failing) + ".</p>\n";
}

}  // namespace section::detail::plot
