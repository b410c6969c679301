// SPDX-License-Identifier: GPL-3.0-or-later
// camber's walls table (a hollow blade's cavities, docs/CAMBER.md "Hollow blades"): declared
// as schema.cpp declares the others, listed by schema::tables() after sides.
#include "section/pipe/schema.h"

#include <array>

namespace section::schema {

namespace {

constexpr std::array<Column<WallRow>, 20> wall_columns{{
    {col::section, "id", "the section id (the plane's index)",
     [](const WallRow& r) { return double(r.section); }},
    {col::loop, "id", "the cavity's loop id within the section (loop 0 is the profile)",
     [](const WallRow& r) { return double(r.loop); }},
    {"area", "area",
     "the area the cavity encloses (the section's material: the params' area less its cavities')",
     [](const WallRow& r) { return r.cavity.area; }},
    {"length", "length", "the cavity's length around", [](const WallRow& r) { return r.cavity.length; }},
    {"wall", "length", "the thinnest wall: the least distance from the cavity to the profile",
     [](const WallRow& r) { return r.cavity.wall; }},
    {"wall_sigma", "length",
     "its standard error through the points' noise: noise x sqrt(the profile's fit's control points over "
     "its points + the cavity's); 0 when the noise is unknown",
     [](const WallRow& r) { return r.sigma; }},
    {"profile_", uv, "length", "where it is thinnest: the profile's point",
     [](const WallRow& r) { return r.cavity.profile_point; }},
    {"cavity_", uv, "length", "... and the cavity's", [](const WallRow& r) { return r.cavity.cavity_point; }},
    {"profile_", xyz, "length", "the profile's point in 3D",
     [](const WallRow& r) { return r.profile_world; }},
    {"cavity_", xyz, "length", "the cavity's point in 3D", [](const WallRow& r) { return r.cavity_world; }},
    {"flags", "code",
     "the checks its wall failed, bits as the params table's flags: the section's that flag the wall "
     "(layers, noise, units, registration, airfoil), noise too when twice wall_sigma exceeds 1.5e-4 of the "
     "profile's size, and wall_measured when a hole in the data lies under its thin stretch; 0 when none",
     [](const WallRow& r) { return double(r.flags); }},
    {"pressure_wall", "length",
     "the thinnest wall to the pressure side (the profile from the LE point to the TE point along "
     "it): with suction_wall, where the cavity sits between the sides (a core shifted toward one side "
     "thins its wall and thickens the other's)",
     [](const WallRow& r) { return r.pressure.wall; }},
    {"pressure_", uv, "length", "where it is thinnest: the pressure side's point",
     [](const WallRow& r) { return r.pressure.profile_point; }},
    {"pressure_flags", "code",
     "the checks the pressure side's wall failed, as flags: wall_measured for a hole under its own thin "
     "stretch",
     [](const WallRow& r) { return double(r.pressure_flags); }},
    {"suction_wall", "length", "the thinnest wall to the suction side",
     [](const WallRow& r) { return r.suction.wall; }},
    {"suction_", uv, "length", "where it is thinnest: the suction side's point",
     [](const WallRow& r) { return r.suction.profile_point; }},
    {"suction_flags", "code", "the checks the suction side's wall failed, as pressure_flags",
     [](const WallRow& r) { return double(r.suction_flags); }},
    {"centroid_", uv, "length",
     "the centroid of the cavity's area: where its core sits (compare's core_shift moves it onto the "
     "nominal's)",
     [](const WallRow& r) { return r.cavity.centroid; }},
    {"centroid_", xyz, "length", "the centroid in 3D", [](const WallRow& r) { return r.centroid_world; }},
    {"centroid_sigma", "length",
     "the centroid's standard error through the points' noise, along its least sure direction: each of "
     "the cavity's measured points moves its boundary by the noise over its share of the length; 0 when "
     "the noise is unknown (compare's core_shift takes its uncertainty from it)",
     [](const WallRow& r) { return r.centroid_sigma; }},
}};

constexpr std::array<Column<WallMapRow>, 11> wall_map_columns{{
    {col::section, "id", "the section id (the plane's index)",
     [](const WallMapRow& r) { return double(r.section); }},
    {col::loop, "id", "the cavity's loop id within the section (as in the walls table)",
     [](const WallMapRow& r) { return double(r.loop); }},
    {"station", "id", "the station's index along the cavity, 0 at its first point (the loop's direction)",
     [](const WallMapRow& r) { return double(r.station); }},
    {"s", "length", "its length along the cavity from station 0 (the stations are evenly spaced)",
     [](const WallMapRow& r) { return r.s; }},
    {"cavity_", uv, "length", "the station: a point of the cavity",
     [](const WallMapRow& r) { return r.cavity_point; }},
    {"cavity_", xyz, "length", "the station in 3D", [](const WallMapRow& r) { return r.cavity_world; }},
    {"wall", "length", "the wall there: the least distance from the station to the profile",
     [](const WallMapRow& r) { return r.wall; }},
    {"profile_", uv, "length", "the profile's nearest point",
     [](const WallMapRow& r) { return r.profile_point; }},
    {"profile_", xyz, "length", "that point in 3D", [](const WallMapRow& r) { return r.profile_world; }},
    {"side", "code",
     "that point's side of the profile: 0 pressure, 1 suction (the profile parted at the LE and TE points)",
     [](const WallMapRow& r) { return double(r.side); }},
    {"flags", "code",
     "the checks the wall there failed, bits as the params table's flags: those of the cavity's walls "
     "(layers, noise, units, registration, airfoil), and wall_measured when a hole in the data lies at the "
     "station or at its nearest point; 0 when none",
     [](const WallMapRow& r) { return double(r.flags); }},
}};

}  // namespace

const TableSchema<WallRow> walls{
    "walls", "camber",
    "one row per cavity of a section (a loop inside its profile: a hollow blade's channel): its thinnest "
    "wall, its thinnest to each side, and its centroid (docs/CAMBER.md, \"Hollow blades\"); written only "
    "for sections that hold one",
    wall_columns};

const TableSchema<WallMapRow> wall_map{
    "wall_map", "camber",
    "each cavity's wall along it: stations evenly along the cavity (CamberOptions::wall_stations, camber "
    "--wall-stations), each with the wall there, its nearest profile point and that point's side "
    "(docs/CAMBER.md, \"Hollow blades\"); written only for sections that hold a cavity",
    wall_map_columns};

}  // namespace section::schema
