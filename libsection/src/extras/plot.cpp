// SPDX-License-Identifier: GPL-3.0-or-later
// SVG and HTML drawings of the sections of a pipe stream (plot.h): the public functions and
// the HTML page. The parts of a section's drawing are in plot_parts.h.
#include "section/extras/plot.h"

#include "plot_parts.h"
#include "section/error.h"
#include "section/io/stream.h"

#include <cmath>
#include <map>
#include <set>

namespace section {

using namespace detail::plot;

namespace {

// Each section's rows, issues and unit in a stream of its own, from one pass over the tables:
// collect then reads one section's rows, not every table's (a page of 5 000 sections took a
// minute). A table without a section column goes to every one.
std::map<int, Stream> by_section(const Stream& stream, const std::vector<int>& ids) {
  std::map<int, Stream> out;
  for (int id : ids) out[id].units = stream.units;
  for (const SectionIssue& issue : stream.issues)
    if (const auto it = out.find(issue.section); it != out.end()) it->second.issues.push_back(issue);
  for (const Table& t : stream.tables) {
    const long cs = t.find_column("section");
    std::map<int, Table*> into;
    for (auto& [id, s] : out) {
      s.tables.push_back(cs < 0 ? t : Table(t.name, t.columns));
      into[id] = &s.tables.back();
    }
    if (cs < 0) continue;
    const std::size_t width = t.columns.size();
    Table* last = nullptr;
    double last_id = std::nan("");
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double id = t.at(r, static_cast<std::size_t>(cs));
      if (id != last_id) {  // rows come grouped by section: one lookup a group
        const auto it =
            std::isfinite(id) && id >= 0 && id <= 2e9 ? into.find(static_cast<int>(id)) : into.end();
        last = it != into.end() && it->first == id ? it->second : nullptr;
        last_id = id;
      }
      if (last)
        last->values.insert(last->values.end(), t.values.begin() + r * width,
                            t.values.begin() + (r + 1) * width);
    }
  }
  return out;
}

void check(const PlotOptions& o) {
  auto bad = [](const std::string& what) { throw Error("plot: " + what); };
  if (!(o.width >= 300 && o.width <= 20000))
    bad("width must lie in [300, 20000] px, got " + trimmed(o.width, 3));
  if (!(o.max_main_height >= 50)) bad("max_main_height must be at least 50 px");
  if (!(o.inset_size == 0 || (o.inset_size >= 80 && o.inset_size <= o.width / 2 - 20)))
    bad("inset_size must be 0 or lie in [80, width/2 - 20] px, got " + trimmed(o.inset_size, 3));
  if (!(o.inset_radii > 1)) bad("inset_radii must exceed 1 so the edge circle fits its inset");
  if (!(o.inset_min_fraction > 0 && o.inset_min_fraction < 0.5))
    bad("inset_min_fraction must lie in (0, 0.5)");
  if (!(o.point_radius >= 0 && o.point_radius <= 20)) bad("point_radius must lie in [0, 20] px");
  if (o.spline_samples < 16) bad("spline_samples must be at least 16");
}

bool has_section(const Stream& stream, int section) {
  const auto ids = plot_sections(stream);
  return std::binary_search(ids.begin(), ids.end(), section);
}

// The page's head: title, style, the stream's history.
std::string html_head(const Stream& stream, std::size_t sections, const std::string& verdict) {
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>libsection: " +
      std::to_string(sections) + " section" + (sections == 1 ? "" : "s") +
      "</title>\n<style>\nbody{font-family:'DejaVu "
      "Sans',Arial,sans-serif;margin:16px;background:#fff;color:#222}\n"
      "table.summary{border-collapse:collapse;margin:8px 0 16px}\n"
      "table.summary td,table.summary th{border:1px solid #ccc;padding:3px 8px;text-align:right}\n"
      "pre.history{background:#f4f4f4;padding:6px;font-size:12px}\n.issue{color:#c00}\n"
      "section{margin-bottom:24px}\nsvg.section-plot{cursor:grab;touch-action:none;max-width:100%;height:"
      "auto}\n"
      "p.hint{color:#666;font-size:13px}\n</style>\n</head>\n<body>\n<h1>Blade sections</h1>\n"
      "<p class=\"hint\">On a drawing: the wheel zooms about the pointer, dragging pans, a double click "
      "shows it whole.</p>\n" +
      verdict;
  if (!stream.history.empty()) {
    h += "<pre class=\"history\">";
    for (const auto& line : stream.history) h += escape(line) + "\n";
    h += "</pre>\n";
  }
  return h;
}

// The summary table: the main parameters of every section, linked to its drawing.
std::string summary_table(const std::vector<SectionData>& data, const std::string& units) {
  const std::string u = escape(units);
  std::string h = "<table class=\"summary\">\n<tr><th>plane</th><th>section</th><th>chord (" + u +
                  ")</th><th>max thickness (" + u + ")</th><th>LE radius (" + u + ")</th><th>TE radius (" +
                  u +
                  ")</th><th>stagger (\xC2\xB0)</th><th>camber angle (\xC2\xB0)</th><th>issues</th></tr>\n";
  for (const auto& d : data) {
    auto cell = [&](const char* key, int decimals) {
      const double x = param(d, key);
      return "<td>" + (std::isfinite(x) ? fixed(x, decimals) : std::string("&ndash;")) + "</td>";
    };
    const std::string link = "<a href=\"#section-" + std::to_string(d.id) + "\">";
    const std::string plane = plane_name(d);
    h += "<tr><td>" + (plane.empty() ? "&ndash;" : link + escape(plane) + "</a>") + "</td><td>" + link +
         std::to_string(d.id) + "</a></td>" + cell("chord", 4) + cell("max_thickness", 4) +
         cell("le_radius", 4) + cell("te_radius", 4) + cell("stagger", 3) + cell("camber_angle", 3) +
         "<td class=\"issue\">" + (d.issues.empty() ? "" : std::to_string(d.issues.size())) + "</td></tr>\n";
  }
  return h + "</table>\n";
}

// Pan and zoom of every drawing, inline (nothing is fetched when the page is viewed): the
// wheel scales the SVG's viewBox about the pointer, a drag moves it, a double click
// restores it.
const char* const pan_zoom = R"(<script>
document.querySelectorAll('svg.section-plot').forEach(function (svg) {
  var home = svg.getAttribute('viewBox').split(' ').map(Number), box = home.slice(), drag = null;
  function show(b) { box = b; svg.setAttribute('viewBox', b.map(function (x) { return x.toFixed(2); }).join(' ')); }
  function user(e) {
    var r = svg.getBoundingClientRect();
    return [box[0] + (e.clientX - r.left) / r.width * box[2], box[1] + (e.clientY - r.top) / r.height * box[3]];
  }
  svg.addEventListener('wheel', function (e) {
    e.preventDefault();
    var p = user(e), k = Math.exp(0.0015 * e.deltaY);
    k = Math.min(Math.max(k, home[2] / 400 / box[2]), home[2] / box[2]);
    show([p[0] - (p[0] - box[0]) * k, p[1] - (p[1] - box[1]) * k, box[2] * k, box[3] * k]);
  }, {passive: false});
  svg.addEventListener('pointerdown', function (e) {
    drag = {x: e.clientX, y: e.clientY, box: box.slice()};
    try { svg.setPointerCapture(e.pointerId); } catch (err) {}  // a pointer the page did not see
  });
  svg.addEventListener('pointermove', function (e) {
    if (!drag) return;
    var r = svg.getBoundingClientRect(), b = drag.box;
    show([b[0] - (e.clientX - drag.x) / r.width * b[2], b[1] - (e.clientY - drag.y) / r.height * b[3], b[2], b[3]]);
  });
  svg.addEventListener('pointerup', function () { drag = null; });
  svg.addEventListener('dblclick', function () { show(home.slice()); });
});
</script>
)";

}  // namespace

std::vector<int> plot_sections(const Stream& stream) {
  std::set<int> ids;
  for (const auto& t : stream.tables) {
    const long c = t.find_column("section");
    if (c < 0) continue;
    for (std::size_t r = 0; r < t.rows(); ++r)
      if (std::isfinite(t.at(r, c))) ids.insert(static_cast<int>(t.at(r, c)));
  }
  for (const auto& i : stream.issues)
    if (i.section >= 0) ids.insert(i.section);
  return {ids.begin(), ids.end()};
}

std::string plot_svg(const Stream& stream, int section, const PlotOptions& options) {
  check(options);
  if (!has_section(stream, section)) {
    std::string ids;
    for (int i : plot_sections(stream)) ids += (ids.empty() ? "" : ", ") + std::to_string(i);
    throw Error("plot: section " + std::to_string(section) + " is not in the stream (" +
                (ids.empty() ? std::string("it holds no section") : "sections: " + ids) + ")");
  }
  return svg_of(collect(stream, section, read_curves(stream)), options);
}

std::string plot_html(const Stream& stream, const PlotOptions& options) {
  check(options);
  const auto ids = plot_sections(stream);
  if (ids.empty()) throw Error("plot: the stream holds no section to draw");
  const Curves curves = read_curves(stream);
  std::map<int, Stream> own = by_section(stream, ids);
  std::vector<SectionData> data;
  for (int id : ids) data.push_back(collect(own.at(id), id, curves));
  std::string h = html_head(stream, ids.size(), blade_verdict_html(data)) + summary_table(data, stream.units);
  for (const auto& d : data) {
    h += "<section id=\"section-" + std::to_string(d.id) + "\">\n";
    try {
      h += svg_of(d, options);
    } catch (const std::exception& e) {
      h += "<p class=\"issue\">section " + std::to_string(d.id) + " could not be drawn: " + escape(e.what()) +
           "</p>\n";
    }
    h += "</section>\n";
  }
  h += pan_zoom;
  h += "</body>\n</html>\n";
  return h;
}

}  // namespace section
