// SPDX-License-Identifier: GPL-3.0-or-later
// blade's tables (docs/BLADE.md): declared as schema.cpp declares the others, listed by
// schema::tables() after compare's.
#include "section/pipe/schema.h"

#include <array>

namespace section::schema {

namespace {

template <auto F>
constexpr auto value = [](const BladeRow& r) { return r.values.*F; };
using V = StackedValues;

constexpr std::array<Column<BladeRow>, 17> blade_columns{{
    {col::section, "id", "the section id (the plane's index)",
     [](const BladeRow& r) { return double(r.section); }},
    {"span", "length",
     "span coordinate of the centroid: its offset along the span direction (rotor: its radius)",
     value<&V::span>},
    {"fraction", "1", "(span - the hub's) / (the tip's - the hub's): 0 at the hub section, 1 at the tip",
     value<&V::fraction>},
    {"stagger", "degrees",
     "angle of the chord line, LE to TE, from the axial direction toward the tangential", value<&V::stagger>},
    {"twist", "degrees", "stagger - the reference section's", value<&V::twist>},
    {"lean", "length", "the centroid's tangential offset from the reference section's", value<&V::lean>},
    {"sweep", "length", "the centroid's axial offset from the reference section's", value<&V::sweep>},
    {"bow", "length", "the centroid's tangential departure from the line through the hub and tip centroids",
     value<&V::bow>},
    {"axial_bow", "length", "its axial departure from that line", value<&V::axial_bow>},
    {"off_line", "length", "distance of the centroid from the fitted stacking line at its span",
     value<&V::off_line>},
    {"centroid_", xyz, "length", "the centroid in 3D", [](const BladeRow& r) { return r.values.centroid; }},
    {"le_", xyz, "length", "the LE point in 3D", [](const BladeRow& r) { return r.values.le; }},
    {"te_", xyz, "length", "the TE point in 3D", [](const BladeRow& r) { return r.values.te; }},
    {"chord", "length", "the section's chord (params)", value<&V::chord>},
    {"max_thickness", "length", "its max thickness (params)", value<&V::max_thickness>},
    {"reference", "flag", "1 for the reference section",
     [](const BladeRow& r) { return r.values.reference ? 1.0 : 0.0; }},
    {"flags", "code", "the blade checks its values failed, one bit each (docs/BLADE.md); 0 when none",
     [](const BladeRow& r) { return double(r.values.flags); }},
}};

template <auto F>
constexpr auto at = [](const StackRow& r) { return r.sample.*F; };
using S = StackSample;

constexpr std::array<Column<StackRow>, 8> stacking_columns{{
    {col::index, "id", "order from the hub to the tip", [](const StackRow& r) { return double(r.index); }},
    {"span", "length", "span coordinate", at<&S::span>},
    {"fraction", "1", "(span - the hub's) / (the tip's - the hub's)", at<&S::fraction>},
    {"centroid_", xyz, "length", "the fitted centroid line there",
     [](const StackRow& r) { return r.sample.centroid; }},
    {"le_", xyz, "length", "the fitted LE line there", [](const StackRow& r) { return r.sample.le; }},
    {"te_", xyz, "length", "the fitted TE line there", [](const StackRow& r) { return r.sample.te; }},
    {"lean", "length", "the centroid line's tangential offset from the reference centroid", at<&S::lean>},
    {"sweep", "length", "its axial offset", at<&S::sweep>},
}};

}  // namespace

const TableSchema<BladeRow> blade{
    "blade", "blade", "one row per section, hub to tip: the whole blade's values there (docs/BLADE.md)",
    blade_columns};
const TableSchema<StackRow> stacking{
    "stacking", "blade", "the fitted stacking lines (centroids, LE and TE points) at even steps of the span",
    stacking_columns};

}  // namespace section::schema
