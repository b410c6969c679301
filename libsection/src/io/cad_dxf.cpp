// SPDX-License-Identifier: GPL-3.0-or-later
// The sections' curves as an ASCII DXF file (AutoCAD 2000, AC1015): the sections and
// tables every reader of DXF R13 and later requires (HEADER with $ACADVER and $HANDSEED,
// CLASSES, TABLES with VPORT *Active, the line types ByBlock, ByLayer and Continuous, layer
// 0, style and dimension style Standard, APPID ACAD and the two block records, BLOCKS with
// *Model_Space and *Paper_Space, OBJECTS with the root dictionary and ACAD_GROUP), then a
// SPLINE (and a 3D POLYLINE) per curve.
#include "section/io/cad.h"

#include "io/byte_source.h"
#include "io/cad_common.h"
#include "section/error.h"
#include "section/io/stream.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace section {

namespace {

// Fixed handles of the structure; layers and entities take theirs from `first_free` on.
namespace handle {
constexpr unsigned layer_table = 0x1, ltype_table = 0x2, appid_table = 0x3, dimstyle_table = 0x4,
                   style_table = 0x5, ucs_table = 0x6, view_table = 0x7, vport_table = 0x8,
                   block_record_table = 0x9, root_dictionary = 0xA, group_dictionary = 0xB,
                   model_record = 0x10, paper_record = 0x11, model_block = 0x12, model_end = 0x13,
                   paper_block = 0x14, paper_end = 0x15, vport = 0x18, ltype = 0x19,  // 0x19..0x1B
    style = 0x1C, appid = 0x1D, dimstyle = 0x1E, layer0 = 0x1F, first_free = 0x20;
}

std::string hex(unsigned h) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%X", h);
  return buf;
}

// DXF text: group code / value line pairs.
struct Dxf {
  std::string text;
  void tag(int code, const std::string& value) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%3d\n", code);
    text += buf;
    text += value;
    text += '\n';
  }
  void num(int code, long value) { tag(code, std::to_string(value)); }
  void real(int code, double value) { tag(code, detail::cad_real(value)); }
  void point(int code, const Eigen::Vector3d& p) {
    real(code, p.x());
    real(code + 10, p.y());
    real(code + 20, p.z());
  }
  // A table's head: `0 TABLE`, its name, handle, owner 0, subclass and entry count.
  void table(const char* name, unsigned h, long count) {
    tag(0, "TABLE");
    tag(2, name);
    tag(5, hex(h));
    tag(330, "0");
    tag(100, "AcDbSymbolTable");
    num(70, count);
  }
  // A table entry's head: type, handle (group 5, 105 for DIMSTYLE), owner and subclasses.
  void entry(const char* type, unsigned h, unsigned owner, const char* subclass, int handle_code = 5) {
    tag(0, type);
    tag(handle_code, hex(h));
    tag(330, hex(owner));
    tag(100, "AcDbSymbolTableRecord");
    tag(100, subclass);
  }
  // An entity's head: type, handle, owner (the model space's record), layer.
  void entity(const char* type, unsigned h, unsigned owner, const std::string& layer) {
    tag(0, type);
    tag(5, hex(h));
    tag(330, hex(owner));
    tag(100, "AcDbEntity");
    tag(8, layer);
  }
};

std::string layer_name(const CadCurve& c) {
  return "section_" + std::to_string(c.section) + (c.loop != 0 ? "_loop_" + std::to_string(c.loop) : "");
}

void vport_and_ltypes(Dxf& d) {
  d.table("VPORT", handle::vport_table, 1);
  d.entry("VPORT", handle::vport, handle::vport_table, "AcDbViewportTableRecord");
  d.tag(2, "*Active");
  d.num(70, 0);
  for (const auto& [code, value] : {std::pair<int, double>{10, 0},
                                    {20, 0},
                                    {11, 1},
                                    {21, 1},
                                    {12, 0},
                                    {22, 0},
                                    {13, 0},
                                    {23, 0},
                                    {14, 1},
                                    {24, 1},
                                    {15, 1},
                                    {25, 1},
                                    {16, 0},
                                    {26, 0},
                                    {36, 1},
                                    {17, 0},
                                    {27, 0},
                                    {37, 0},
                                    {40, 100},
                                    {41, 1.5},
                                    {42, 50}})
    d.real(code, value);
  d.tag(0, "ENDTAB");
  d.table("LTYPE", handle::ltype_table, 3);
  unsigned h = handle::ltype;
  for (const char* name : {"ByBlock", "ByLayer", "Continuous"}) {
    d.entry("LTYPE", h++, handle::ltype_table, "AcDbLinetypeTableRecord");
    d.tag(2, name);
    d.num(70, 0);
    d.tag(3, name[0] == 'C' ? "Solid line" : "");
    d.num(72, 65);
    d.num(73, 0);
    d.real(40, 0);
  }
  d.tag(0, "ENDTAB");
}

void layers(Dxf& d, const std::set<std::string>& names, unsigned& next) {
  d.table("LAYER", handle::layer_table, static_cast<long>(names.size()) + 1);
  auto layer = [&](const std::string& name, unsigned h) {
    d.entry("LAYER", h, handle::layer_table, "AcDbLayerTableRecord");
    d.tag(2, name);
    d.num(70, 0);
    d.num(62, 7);
    d.tag(6, "Continuous");
  };
  layer("0", handle::layer0);
  for (const auto& name : names) layer(name, next++);
  d.tag(0, "ENDTAB");
}

void other_tables(Dxf& d) {
  d.table("STYLE", handle::style_table, 1);
  d.entry("STYLE", handle::style, handle::style_table, "AcDbTextStyleTableRecord");
  d.tag(2, "Standard");
  d.num(70, 0);
  d.real(40, 0);
  d.real(41, 1);
  d.real(50, 0);
  d.num(71, 0);
  d.real(42, 2.5);
  d.tag(3, "txt");
  d.tag(4, "");
  d.tag(0, "ENDTAB");
  d.table("VIEW", handle::view_table, 0);
  d.tag(0, "ENDTAB");
  d.table("UCS", handle::ucs_table, 0);
  d.tag(0, "ENDTAB");
  d.table("APPID", handle::appid_table, 1);
  d.entry("APPID", handle::appid, handle::appid_table, "AcDbRegAppTableRecord");
  d.tag(2, "ACAD");
  d.num(70, 0);
  d.tag(0, "ENDTAB");
  d.table("DIMSTYLE", handle::dimstyle_table, 1);
  d.tag(100, "AcDbDimStyleTable");
  d.entry("DIMSTYLE", handle::dimstyle, handle::dimstyle_table, "AcDbDimStyleTableRecord", 105);
  d.tag(2, "Standard");
  d.num(70, 0);
  d.tag(0, "ENDTAB");
  d.table("BLOCK_RECORD", handle::block_record_table, 2);
  for (const auto& [h, name] : {std::pair<unsigned, const char*>{handle::model_record, "*Model_Space"},
                                {handle::paper_record, "*Paper_Space"}}) {
    d.entry("BLOCK_RECORD", h, handle::block_record_table, "AcDbBlockTableRecord");
    d.tag(2, name);
  }
  d.tag(0, "ENDTAB");
}

void blocks(Dxf& d) {
  for (const auto& [record, begin, end, name] :
       {std::tuple<unsigned, unsigned, unsigned, const char*>{handle::model_record, handle::model_block,
                                                              handle::model_end, "*Model_Space"},
        {handle::paper_record, handle::paper_block, handle::paper_end, "*Paper_Space"}}) {
    d.entity("BLOCK", begin, record, "0");
    d.tag(100, "AcDbBlockBegin");
    d.tag(2, name);
    d.num(70, 0);
    d.point(10, Eigen::Vector3d::Zero());
    d.tag(3, name);
    d.tag(1, "");
    d.entity("ENDBLK", end, record, "0");
    d.tag(100, "AcDbBlockEnd");
  }
}

void spline(Dxf& d, const CadCurve& c, const detail::CadSpline& s, unsigned h) {
  d.entity("SPLINE", h, handle::model_record, layer_name(c));
  d.tag(100, "AcDbSpline");
  d.point(210, c.frame.n);
  d.num(70, 8 + (s.closed ? 1 : 0));  // planar, closed
  d.num(71, s.degree);
  d.num(72, static_cast<long>(s.knots.size()));
  d.num(73, static_cast<long>(s.control.size()));
  d.num(74, 0);
  d.real(42, 1e-10);
  d.real(43, 1e-10);
  for (double k : s.knots) d.real(40, k);
  for (const auto& p : s.control) d.point(10, p);
}

// The parameters of c's polyline vertices; `budget`: the vertices the file may still take.
std::vector<double> polyline_parameters(const CadCurve& c, const CadOptions& o, std::size_t& budget) {
  // A curve's own limit is flatten's; the file's budget binds when less is left of it.
  const std::size_t own = max_flatten_points, limit = std::min(own, budget);
  std::vector<double> ts;
  try {
    ts = flatten(c.spline, o.polyline_tolerance, limit);
  } catch (const Error& e) {
    std::string why = e.what();
    if (limit < own)
      why +=
          " (the file's polylines may hold " + std::to_string(o.max_polyline_vertices) + " vertices in all)";
    throw Error("dxf: the polyline of section " + std::to_string(c.section) + " loop " +
                std::to_string(c.loop) + ": " + why);
  }
  budget -= ts.size();
  return ts;
}

void polyline(Dxf& d, const CadCurve& c, const std::vector<double>& ts, unsigned& next) {
  const std::string layer = layer_name(c);
  const unsigned owner = next++;
  d.entity("POLYLINE", owner, handle::model_record, layer);
  d.tag(100, "AcDb3dPolyline");
  d.num(66, 1);
  d.point(10, Eigen::Vector3d::Zero());
  d.num(70, 8 + (c.spline.closed ? 1 : 0));  // 3D, closed
  for (double t : ts) {
    d.entity("VERTEX", next++, owner, layer);
    d.tag(100, "AcDbVertex");
    d.tag(100, "AcDb3dPolylineVertex");
    d.point(10, c.frame.to_world(c.spline.point(t)));
    d.num(70, 32);
  }
  d.entity("SEQEND", next++, owner, layer);
}

void section(Dxf& out, const char* name, const std::string& body) {
  out.tag(0, "SECTION");
  out.tag(2, name);
  out.text += body;
  out.tag(0, "ENDSEC");
}

void finite_or_refuse(double x) {
  if (!std::isfinite(x)) detail::cad_real(x);  // (its message)
}

// What the file needs before its first byte: every curve's clamped form and polyline,
// checked, so that a curve the file cannot hold is refused before anything is written.
struct Prepared {
  const detail::CadUnit* unit = nullptr;
  std::vector<detail::CadSpline> splines;
  std::vector<std::vector<double>> polylines;  // parameters of each curve's vertices
};

Prepared prepare_curves(const std::vector<CadCurve>& curves, const CadOptions& options) {
  Prepared p;
  p.unit = &detail::cad_unit(options.units);
  if (!(options.polyline_tolerance >= 0) || !std::isfinite(options.polyline_tolerance))
    throw Error("dxf: the polyline tolerance must be 0 (none) or a length above 0, got " +
                format_number(options.polyline_tolerance));
  std::size_t budget = options.max_polyline_vertices;
  for (const auto& c : curves) {
    detail::CadSpline s = detail::cad_spline(c);
    for (double k : s.knots) finite_or_refuse(k);
    for (const auto& q : s.control)
      for (int i = 0; i < 3; ++i) finite_or_refuse(q[i]);
    for (int i = 0; i < 3; ++i) finite_or_refuse(c.frame.n[i]);
    p.splines.push_back(std::move(s));
    p.polylines.push_back(options.polyline_tolerance > 0 ? polyline_parameters(c, options, budget)
                                                         : std::vector<double>{});
  }
  return p;
}

// prepare_curves, its errors naming options.source (the input) when they do not already.
Prepared prepare(const std::vector<CadCurve>& curves, const CadOptions& options) {
  try {
    return prepare_curves(curves, options);
  } catch (const Error& e) {
    const std::string what = e.what();
    if (options.source.empty() || what.find(options.source) != std::string::npos) throw;
    throw Error(options.source + ": " + what);
  }
}

// The file, piece by piece to `put`: the header (whose $HANDSEED follows the last handle),
// the tables and blocks, then the entities a curve at a time, then the objects.
template <class Put>
void emit(const std::vector<CadCurve>& curves, const CadOptions& options, const Prepared& p, Put&& put) {
  const bool polylines = options.polyline_tolerance > 0;
  unsigned next = handle::first_free;
  std::set<std::string> names;
  for (const auto& c : curves) names.insert(layer_name(c));
  Dxf tables, blocks_section, objects;
  vport_and_ltypes(tables);
  layers(tables, names, next);
  other_tables(tables);
  blocks(blocks_section);
  unsigned seed = next;
  for (std::size_t k = 0; k < curves.size(); ++k)
    seed += 1 + (polylines ? 2 + static_cast<unsigned>(p.polylines[k].size()) : 0);
  objects.tag(0, "DICTIONARY");
  objects.tag(5, hex(handle::root_dictionary));
  objects.tag(330, "0");
  objects.tag(100, "AcDbDictionary");
  objects.num(281, 1);
  objects.tag(3, "ACAD_GROUP");
  objects.tag(350, hex(handle::group_dictionary));
  objects.tag(0, "DICTIONARY");
  objects.tag(5, hex(handle::group_dictionary));
  objects.tag(330, hex(handle::root_dictionary));
  objects.tag(100, "AcDbDictionary");
  objects.num(281, 1);

  Dxf header, head;
  header.tag(9, "$ACADVER");
  header.tag(1, "AC1015");
  header.tag(9, "$HANDSEED");
  header.tag(5, hex(seed));
  header.tag(9, "$INSUNITS");
  header.num(70, p.unit->dxf);
  header.tag(9, "$MEASUREMENT");
  header.num(70, p.unit->iges == 1 ? 0 : 1);  // 0 imperial, 1 metric
  section(head, "HEADER", header.text);
  section(head, "CLASSES", "");
  section(head, "TABLES", tables.text);
  section(head, "BLOCKS", blocks_section.text);
  head.tag(0, "SECTION");
  head.tag(2, "ENTITIES");
  put(std::move(head.text));
  for (std::size_t k = 0; k < curves.size(); ++k) {
    Dxf d;
    spline(d, curves[k], p.splines[k], next++);
    if (polylines) polyline(d, curves[k], p.polylines[k], next);
    put(std::move(d.text));
  }
  Dxf tail;
  tail.tag(0, "ENDSEC");
  section(tail, "OBJECTS", objects.text);
  tail.tag(0, "EOF");
  put(std::move(tail.text));
}

}  // namespace

std::string format_dxf(const std::vector<CadCurve>& curves, const CadOptions& options) {
  const Prepared p = prepare(curves, options);
  // The pieces joined in one allocation: grown by doubling the text held up to twice the
  // entities' beside them (575 MB for the 95 MB of 1 000 sections with polylines).
  std::vector<std::string> pieces;
  std::size_t size = 0;
  emit(curves, options, p, [&](std::string&& piece) {
    size += piece.size();
    pieces.push_back(std::move(piece));
  });
  std::string text;
  text.reserve(size);
  for (auto& piece : pieces) {
    text += piece;
    std::string().swap(piece);
  }
  return text;
}

void write_dxf(const std::string& path, const std::vector<CadCurve>& curves, const CadOptions& options) {
  const Prepared p = prepare(curves, options);
  detail::ByteSink out(path, "");
  emit(curves, options, p, [&](std::string&& piece) { out.write(piece); });
  out.close();
}

}  // namespace section
