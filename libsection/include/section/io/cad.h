// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/cad.h
/// The sections' curves in the files a CAD system imports: DXF (SPLINE entities with the
/// B-spline's degree, knots and control points, and 3D polylines) and IGES (entity 126,
/// the rational B-spline curve, with weights 1), each curve in 3D on its section's plane.
/// docs/EXPORT.md says what is written.
#include "section/bspline.h"
#include "section/frame.h"

#include <string>
#include <vector>

namespace section {

/// One curve to export: a loop's B-spline in its section's plane.
struct CadCurve {
  int section = 0;  ///< the section id (the DXF layer `section_S`, the IGES entity subscript)
  int loop = 0;     ///< the loop id within the section, 0 the profile
  Frame frame;      ///< maps the spline's (u, v) to 3D
  BSpline spline;   ///< the curve in (u, v), as the stream stores it (closed or open)
};

/// What the CAD writers add around the curves.
struct CadOptions {
  std::string units = "mm";       ///< the coordinates' length unit: mm, cm, m, in or um
  double polyline_tolerance = 0;  ///< DXF: also a 3D polyline per curve within this length of
                                  ///< it (bspline.h, flatten); 0 = splines only
  /// DXF: the polylines' vertices in all, at most (about 130 bytes each): a tolerance far below
  /// the curves' size on many sections grew the text without bound
  std::size_t max_polyline_vertices = 2000000;
  std::string source;  ///< the input's name: in the IGES file's header, and leading the DXF writers' errors
  std::string timestamp = "19700101.000000";  ///< IGES: date and time of the file, YYYYMMDD.HHNNSS (UTC)
};

/// The curves as an ASCII DXF file (AutoCAD 2000, AC1015): each curve one SPLINE entity
/// (its clamped form, bspline.h `clamped`: degree, knots, 3D control points; flags planar
/// and, for a closed loop, closed; extrusion the plane's normal) on the layer `section_S`
/// (`section_S_loop_L` for loops other than 0), followed by a closed 3D POLYLINE when
/// options.polyline_tolerance > 0. Throws section::Error for an unknown unit, a
/// non-finite number, a polyline tolerance that is not 0 or above, or polylines that would
/// need more than options.max_polyline_vertices vertices, the message led by options.source
/// when that is given.
std::string format_dxf(const std::vector<CadCurve>& curves, const CadOptions& options = {});

/// format_dxf's file written to `path` ("-" = standard output) as it is made, a curve at a
/// time: its text is never held whole (1 000 sections with polylines, 95 MB of DXF).
/// Everything format_dxf refuses is refused before the first byte; a file is written under
/// a temporary name in its directory and renamed when whole, so that a failure leaves none.
/// Throws section::Error as format_dxf, and when the output cannot be written.
void write_dxf(const std::string& path, const std::vector<CadCurve>& curves, const CadOptions& options = {});

/// The curves as an IGES 5.3 file (fixed 80-column ASCII): each curve one entity 126
/// (rational B-spline curve, form 0) with the clamped form's knots and 3D control points,
/// all weights 1, flagged planar (with the plane's normal), closed for a closed loop and
/// polynomial; its label `S<section>L<loop>`, its subscript the section id. Throws
/// section::Error for an unknown unit or a non-finite number.
std::string format_iges(const std::vector<CadCurve>& curves, const CadOptions& options = {});

}  // namespace section
