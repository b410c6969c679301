// SPDX-License-Identifier: GPL-3.0-or-later
#include "args/blade_args.h"

#include "args/camber_args.h"  // numbers()

namespace section::tool {

const char* const BladeArgs::description =
    "blade: the whole blade from its sections: stacking line, twist, lean, bow, sweep\n"
    "(docs/BLADE.md).\n\n"
    "Reads a stream written by camber (docs/FORMAT.md) holding several sections of one\n"
    "blade, takes each section's centroid, LE and TE points to 3D through its frame, and\n"
    "writes per section, from hub to tip: span, stagger and twist (from the reference\n"
    "section), lean and sweep (the centroid's tangential and axial offsets from the\n"
    "reference's), bow and axial bow (its departures from the line through the hub and tip\n"
    "centroids), chord and max thickness; the centroid, LE and TE lines are fitted as smooth\n"
    "curves along the span (table 'stacking', --lines, --plot).\n\n"
    "Directions: a planar stack (default) has its span along the planes' normal, axial along\n"
    "the reference frame's u, tangential = span x axial (v for planes normal to z). With\n"
    "--axis (a rotor) axial is the axis, span the radius and tangential the circumferential\n"
    "direction (radial x axial), tangential distances radius x angle.\n\n"
    "A value that rests on a value camber flagged, or that the sections cannot define (fewer\n"
    "than 3 for a bow, sections out of span order), is flagged in the 'flags' column, marked\n"
    "'!' in the table and named in an issue; it is never given bare.\n\n"
    "Exit status: 0 every section has params, 1 bad data (fewer than 2 measured sections, no\n"
    "params table, an empty stream), 2 bad usage, 3 the output is written but some sections\n"
    "have no params (exit 0 with --allow-partial).\n\n"
    "Example: slice blade.ply --count 9 | smooth | fitspline | camber | blade --plot blade.svg";

void BladeArgs::declare(CLI::App& app) {
  add_common(app, common);
  app.add_option("--reference", options.reference,
                 "Section id whose twist, lean and sweep are 0 (default: the first by span, the hub)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--axis", axis,
                 "px,py,pz,dx,dy,dz: the machine axis (a point and a direction) of a rotor: axial along "
                 "it, span the radius, tangential circumferential")
      ->check(CLI::Validator(
          [](std::string& text) {
            try {
              const auto v = numbers(text, "--axis");
              if (v.size() != 6) return std::string("--axis: expected 6 numbers px,py,pz,dx,dy,dz");
              if (v[3] == 0 && v[4] == 0 && v[5] == 0) return std::string("--axis: the direction is zero");
              return std::string();
            } catch (const CLI::ValidationError& e) {
              return std::string(e.what());
            }
          },
          ""));
  add_checked(app, "--control-points", options.control_points,
              "Control points of each fitted line; 0 = min(sections, 4 + sections / 4)",
              CLI::NonNegativeNumber);
  add_checked(app, "--samples", options.samples, "Points of each fitted line in the table 'stacking'",
              CLI::Range(2, 100000));
  add_checked(app, "--off-line", options.off_line,
              "mm: a centroid farther than this from its fitted line is flagged (check curve)", positive);
  app.add_option("--plot", plot_file, "Also draw the stacking line and the distributions to FILE (SVG)");
  app.add_option("--lines", lines_file, "Also write the 'stacking' table (the fitted lines) to FILE (CSV)");
  app.add_option("--format", format,
                 "What to write to the output: table (for people: mm to 4 decimals, degrees to 3, '!' "
                 "after a flagged value), csv (the blade table, full precision), json (the blade rows and "
                 "issues per section) or stream (the input stream with the tables blade and stacking); "
                 "default table when the output is a terminal, else csv")
      ->check(CLI::IsMember({"stream", "table", "csv", "json"}));
  add_allow_partial(app, allow_partial);
  app.callback([this] {
    if (axis.empty()) return;
    const auto v = numbers(axis, "--axis");
    options.rotor = true;
    options.axis_point = {v[0], v[1], v[2]};
    options.axis_direction = {v[3], v[4], v[5]};
  });
}

}  // namespace section::tool
