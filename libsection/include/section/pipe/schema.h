// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/schema.h
/// The stream's tables, each declared once (libsection/src/pipe/schema.cpp): its name, the
/// tool that writes it and its columns as {name, unit, meaning, getter} (a 2D or 3D point is
/// one entry over two or three columns). The header rows, the row writers, the readers'
/// column lookups and docs/FORMAT.md's column tables all come from those lists
/// (tests/test_schema.cpp holds FORMAT.md to them).
#include "section/cavity.h"
#include "section/checks.h"
#include "section/compare.h"
#include "section/fit_spline.h"
#include "section/frame.h"
#include "section/io/stream.h"
#include "section/morphology.h"
#include "section/params.h"
#include "section/smooth.h"
#include "section/stacking.h"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace section {

/// Section frames of a stream (table "frames"), by section id; a section on a surface of
/// revolution (its `surface` column set) gets its surface, with its meridian from the
/// "meridians" table. Throws section::Error when the table is missing, a frame is not
/// right-handed orthonormal or a surface is incomplete.
std::map<int, Frame> frames(const Stream& stream);

/// Adds or replaces the "frames" table from frames by section id (and the "meridians" table
/// when a frame lies on a surface of revolution; planes alone write neither its columns nor it).
void put_frames(Stream& stream, const std::map<int, Frame>& frames);

/// Converts a stream in another length unit (`# units`, units.h) to mm, the unit every
/// stage's defaults are stated in: each table's columns by their unit's power of length
/// (length, area, length^2, 1/length). Throws section::Error for an unknown unit.
void convert_to_mm(Stream& stream);

/// `stream` itself when its unit is mm, else `copy`, made of it and converted to mm: for a
/// stage that reads a stream it may not change (a nominal) in the unit of its options.
const Stream& in_mm(const Stream& stream, Stream& copy);

namespace schema {

/// Names of the columns that readers look up (the lists use them; u and v are a point's).
namespace col {
inline constexpr const char* section = "section";
inline constexpr const char* loop = "loop";
inline constexpr const char* index = "index";
inline constexpr const char* u = "u";
inline constexpr const char* v = "v";
inline constexpr const char* offset = "offset";
inline constexpr const char* degree = "degree";
inline constexpr const char* closed = "closed";
inline constexpr const char* rms = "rms";
inline constexpr const char* layers = "layers";
inline constexpr const char* layers_length = "layers_length";
inline constexpr const char* knot = "knot";
inline constexpr const char* t_start = "t_start";
inline constexpr const char* t_end = "t_end";
inline constexpr const char* length = "length";
}  // namespace col

/// Tags of a point spread over columns: NAME_u, NAME_v (`uv`) or NAME_x, NAME_y, NAME_z (`xyz`).
struct Uv {};
struct Xyz {};
inline constexpr Uv uv{};
inline constexpr Xyz xyz{};

/// One column, or a point spread over two or three: what docs/FORMAT.md lists of it, and
/// its value in a row made from `Row`.
template <class Row>
struct Column {
  constexpr Column() = default;
  /// A column of one number.
  constexpr Column(const char* column_name, const char* unit_name, const char* what,
                   double (*getter)(const Row&))
      : name(column_name), unit(unit_name), meaning(what), get(getter) {}
  /// A 2D point: columns PREFIXu, PREFIXv ("le_" -> le_u, le_v; "" -> u, v).
  constexpr Column(const char* prefix, Uv, const char* unit_name, const char* what,
                   Eigen::Vector2d (*getter)(const Row&))
      : name(prefix), axes("uv"), unit(unit_name), meaning(what), get2(getter) {}
  /// A 3D point: columns PREFIXx, PREFIXy, PREFIXz.
  constexpr Column(const char* prefix, Xyz, const char* unit_name, const char* what,
                   Eigen::Vector3d (*getter)(const Row&))
      : name(prefix), axes("xyz"), unit(unit_name), meaning(what), get3(getter) {}

  const char* name = "";     ///< header name, or a point's prefix
  const char* axes = "";     ///< "" for one number, "uv" or "xyz" for a point
  const char* unit = "";     ///< one of the units FORMAT.md lists ("id", "length", "degrees", ...)
  const char* meaning = "";  ///< one line of FORMAT.md
  double (*get)(const Row&) = nullptr;
  Eigen::Vector2d (*get2)(const Row&) = nullptr;
  Eigen::Vector3d (*get3)(const Row&) = nullptr;
};

/// A column (or a point's columns, "le_x, le_y, le_z") as docs/FORMAT.md lists it.
struct ColumnDoc {
  std::string name;
  const char* unit;
  const char* meaning;
};

/// A table as docs/FORMAT.md lists it: name, writer, meaning, columns in order.
struct TableDoc {
  const char* name;
  const char* written_by;
  const char* meaning;
  std::vector<ColumnDoc> columns;
};

/// A stream table: its name, the tool that writes it, what a row is and its columns.
template <class Row>
struct TableSchema {
  template <class List>
  constexpr TableSchema(const char* table_name, const char* writer, const char* what, const List& list)
      : name(table_name),
        written_by(writer),
        meaning(what),
        columns(std::data(list)),
        count(std::size(list)) {}

  const char* name;        ///< e.g. "points"
  const char* written_by;  ///< the tool, for the error when the table is missing
  const char* meaning;     ///< one line of FORMAT.md
  const Column<Row>* columns;
  std::size_t count;  ///< entries of `columns`

  /// The header: every column's name, or those up to `last`.
  std::vector<std::string> names(const char* last = nullptr) const;
  /// An empty table with this name and header (see names()).
  Table table(const char* last = nullptr) const { return Table(name, names(last)); }
  /// Appends a row's values, one per column, to a table's values.
  void append(std::vector<double>& values, const Row& row) const;
  /// Adds a row to `t`, made by table(): as many values as it has columns.
  void add(Table& t, const Row& row) const;
  /// The table in `stream`, or nullptr.
  const Table* find(const Stream& stream) const { return stream.find(name); }
  /// The table in `stream`; throws section::Error naming the tool that writes it when absent.
  const Table& get(const Stream& stream) const { return stream.get(name, written_by); }
  /// What FORMAT.md lists of the table.
  TableDoc doc() const;
};

/// What each table's row is made from (the getters read these).
struct FrameRow {
  int section;
  const Frame& frame;
};
struct MeridianRow {
  int section;
  std::size_t index;
  Eigen::Vector2d point;  ///< (axial, radius)
};
struct LoopRow {
  int section;
  std::size_t loop;  ///< index into morphology.loops
  const MorphologyResult& morphology;
};
struct PointRow {
  int section;
  std::size_t loop, index;
  Eigen::Vector2d point, normal;
  double offset;  ///< signed distance from the plane before the gap fill carried it; 0 for the slab's
};
struct SkeletonRow {
  int section;
  std::size_t index;
  Eigen::Vector2d point;
  double radius;
};
/// A point of a loop in order: smoothed, spline_ctrl.
struct LoopPoint {
  int section, loop;
  std::size_t index;
  Eigen::Vector2d point;
};
struct SmoothStatsRow {
  int section, loop;
  const SmoothResult& result;
};
struct SplineRow {
  int section, loop;
  const FitSplineResult& fit;
};
struct KnotRow {
  int section, loop;
  std::size_t index;
  double knot;
};
struct GapRow {
  int section, loop;
  std::size_t index;
  const FitSplineResult::Gap& gap;
};
struct SampleRow {
  int section, loop, index;
  double t;
  Eigen::Vector2d point;
  Eigen::Vector3d world;
  Eigen::Vector2d normal;
  double curvature;
};
struct CamberRow {
  int section;
  std::size_t index;
  double s;
  Eigen::Vector2d point;
  Eigen::Vector3d world;
  double radius;
};
struct ParamsRow {
  int section;
  const SectionParams& params;
  const CamberResult& camber;
  Eigen::Vector3d le, te, centroid;  ///< the edge points and the centroid in 3D
  double le_unmeasured, te_unmeasured;
  CheckBits flags;     ///< the checks the section failed (section/checks.h)
  ValueSigmas sigmas;  ///< the values' standard errors through the points' noise
};
struct ThicknessRow {
  int section;
  std::size_t index;
  const ThicknessStation& station;
  CheckBits flags;  ///< the checks its thickness failed (section/checks.h)
};
struct SideRow {
  int section, side;  ///< side 0 pressure, 1 suction
  std::size_t index;
  Eigen::Vector2d point;
};
struct WallRow {
  int section, loop;
  const Cavity& cavity;
  double sigma;  ///< the wall's standard error through the points' noise (0: unknown)
  Eigen::Vector3d profile_world, cavity_world;  ///< the wall's two ends in 3D
  CheckBits flags;                              ///< the checks its wall failed (section/checks.h)
  const CavityWall& pressure;                   ///< the thinnest wall to the pressure side
  const CavityWall& suction;                    ///< ... and to the suction side
  CheckBits pressure_flags, suction_flags;      ///< the checks each failed
  Eigen::Vector3d centroid_world;               ///< the cavity's centroid in 3D
  double centroid_sigma;                        ///< its standard error through the noise (0: unknown)
};
struct WallMapRow {
  int section, loop;
  std::size_t station;
  double s;                       ///< length along the cavity from station 0
  Eigen::Vector2d cavity_point;   ///< the station
  Eigen::Vector3d cavity_world;   ///< ... in 3D
  double wall;                    ///< its least distance to the profile
  Eigen::Vector2d profile_point;  ///< the profile's nearest point
  Eigen::Vector3d profile_world;  ///< ... in 3D
  int side;                       ///< that point's side: 0 pressure, 1 suction
  CheckBits flags;                ///< the checks its wall failed (section/checks.h)
};

// compare's rows (docs/COMPARE.md). Verdict codes: -1 no tolerance, 0 pass, 1 fail,
// 2 not measured; `bounds` of a tolerance: 0 none, 1 low only, 2 high only, 3 both.
struct FitRow {
  int section;
  const FitResult& fit;
  int method, freedom;    ///< FitMethod, FitFreedom
  bool whole;             ///< the whole-blade fit
  Eigen::Vector3d shift;  ///< the translation in 3D
  int points, outliers;
};
struct DeviationRow {
  int section;
  std::size_t index;  ///< the point's row among the section's loop-0 points
  const PointDeviation& point;
  Eigen::Vector3d world;  ///< the foot in 3D
};
struct ZoneRow {
  int section;
  int zone;  ///< Zone
  const ZoneResult& result;
  const Tolerance* band;  ///< the profile tolerance, or nullptr
  int verdict;
  const Tolerance* form;  ///< the form tolerance, or nullptr
  int form_verdict;
};
struct ComparedRow {
  int section;
  int item;  ///< the compared value's code (docs/FORMAT.md)
  bool measured;
  double value, nominal, deviation;
  const Tolerance* tolerance;
  int verdict;
  double uncertainty;              ///< the expanded uncertainty of what the limits bound (0: none known)
  CheckBits flags, nominal_flags;  ///< camber's checks flagging the measured and the nominal value
};
struct VerdictRow {
  int section;
  int verdict;  ///< the section's: 1 when a value failed, else 2 when one was not measured, else 3 when one
                ///< was uncertain, else 0 (-1: none toleranced)
  int passed, failed, not_measured, uncertain;
};

// blade's rows (docs/BLADE.md).
struct BladeRow {
  int section;
  const StackedValues& values;
};
struct StackRow {
  std::size_t index;
  const StackSample& sample;
};

// The tables, in the order the tools write them.
extern const TableSchema<FrameRow> frames;
extern const TableSchema<MeridianRow> meridians;
extern const TableSchema<LoopRow> loops;
extern const TableSchema<PointRow> points;
extern const TableSchema<SkeletonRow> skeleton;
extern const TableSchema<LoopPoint> smoothed;
extern const TableSchema<SmoothStatsRow> smooth_stats;
extern const TableSchema<SplineRow> splines;
extern const TableSchema<KnotRow> spline_knots;
extern const TableSchema<LoopPoint> spline_ctrl;
extern const TableSchema<GapRow> gaps;
extern const TableSchema<SampleRow> samples;
extern const TableSchema<CamberRow> camber;
extern const TableSchema<ParamsRow> params;
extern const TableSchema<ThicknessRow> thickness;
extern const TableSchema<SideRow> sides;
extern const TableSchema<WallRow> walls;
extern const TableSchema<WallMapRow> wall_map;
// compare's tables.
extern const TableSchema<FitRow> fits;
extern const TableSchema<DeviationRow> deviations;
extern const TableSchema<ZoneRow> zones;
extern const TableSchema<ComparedRow> compared;
extern const TableSchema<VerdictRow> verdicts;
// blade's tables (src/pipe/schema_blade.cpp).
extern const TableSchema<BladeRow> blade;
extern const TableSchema<StackRow> stacking;

/// Every table above as docs/FORMAT.md lists it, in that order.
std::vector<TableDoc> tables();

}  // namespace schema
}  // namespace section
