#pragma once
/// @file pipe/schema.h
/// The stream's tables, each declared once (libsection/src/pipe/schema.cpp): its name, the
/// tool that writes it and its columns as {name, unit, meaning, getter}. The header rows,
/// the row writers, the readers' column lookups and docs/FORMAT.md's column tables all come
/// from those lists (tests/test_schema.cpp holds FORMAT.md to them).
#include "section/fit_spline.h"
#include "section/frame.h"
#include "section/io/stream.h"
#include "section/morphology.h"
#include "section/params.h"
#include "section/smooth.h"

#include <Eigen/Core>

#include <cstddef>
#include <map>
#include <vector>

namespace section {

/// Section frames of a stream (table "frames"), by section id. Throws section::Error when
/// the table is missing or a frame is not right-handed orthonormal.
std::map<int, Frame> frames(const Stream& stream);

/// Adds or replaces the "frames" table from frames by section id.
void put_frames(Stream& stream, const std::map<int, Frame>& frames);

namespace schema {

/// Names of the columns that readers look up (the column lists use them too).
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

/// One column: what docs/FORMAT.md lists of it, and its value in a row made from `Row`.
template <class Row>
struct Column {
  const char* name;     ///< header name
  const char* unit;     ///< one of the units FORMAT.md lists ("id", "length", "degrees", ...)
  const char* meaning;  ///< one line of FORMAT.md
  double (*get)(const Row&);
};

/// A column as docs/FORMAT.md lists it.
struct ColumnDoc {
  const char* name;
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
  template <std::size_t N>
  constexpr TableSchema(const char* table_name, const char* writer, const char* what,
                        const Column<Row> (&list)[N])
      : name(table_name), written_by(writer), meaning(what), columns(list), count(N) {}

  const char* name;        ///< e.g. "points"
  const char* written_by;  ///< the tool, for the error when the table is missing
  const char* meaning;     ///< one line of FORMAT.md
  const Column<Row>* columns;
  std::size_t count;       ///< columns

  const Column<Row>* begin() const { return columns; }
  const Column<Row>* end() const { return columns + count; }
  /// An empty table with this name and header: every column, or those up to `last`.
  Table table(const char* last = nullptr) const {
    Table t(name, {});
    for (const auto& c : *this) {
      t.columns.emplace_back(c.name);
      if (last && t.columns.back() == last) break;
    }
    return t;
  }
  /// Appends a row's values, one per column, to a table's values.
  void append(std::vector<double>& values, const Row& row) const {
    for (const auto& c : *this) values.push_back(c.get(row));
  }
  /// Adds a row to `t`, made by table(): as many values as it has columns.
  void add(Table& t, const Row& row) const {
    for (std::size_t c = 0; c < t.columns.size(); ++c) t.values.push_back(columns[c].get(row));
  }
  /// The table in `stream`, or nullptr.
  const Table* find(const Stream& stream) const { return stream.find(name); }
  /// The table in `stream`; throws section::Error naming the tool that writes it when absent.
  const Table& get(const Stream& stream) const { return stream.get(name, written_by); }
  /// What FORMAT.md lists of the table.
  TableDoc doc() const {
    TableDoc d{name, written_by, meaning, {}};
    for (const auto& c : *this) d.columns.push_back({c.name, c.unit, c.meaning});
    return d;
  }
};

/// What each table's row is made from (the getters read these).
struct FrameRow {
  int section;
  const Frame& frame;
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
};
struct ThicknessRow {
  int section;
  std::size_t index;
  const ThicknessStation& station;
};
struct SideRow {
  int section, side;  ///< side 0 pressure, 1 suction
  std::size_t index;
  Eigen::Vector2d point;
};

// The tables, in the order the tools write them.
extern const TableSchema<FrameRow> frames;
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

/// Every table above as docs/FORMAT.md lists it, in that order.
std::vector<TableDoc> tables();

}  // namespace schema
}  // namespace section
