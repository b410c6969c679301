// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file compare.h
/// A measured section against its nominal (docs/COMPARE.md): a rigid best fit of the
/// measured points onto the nominal profile in the section's plane (least squares, minimum
/// zone or weighted, with the degrees of freedom chosen), each point's signed deviation
/// along the nominal's outward normal before and after the fit, the profile zones (leading
/// and trailing edge, pressure and suction side, whole) with their deviations, form error
/// and coverage, and the verdict of a value against its tolerance. compare_blade fits all
/// the sections of a blade with one rigid motion.
#include "section/bspline.h"
#include "section/frame.h"

#include <Eigen/Core>

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace section {

/// How the measured section is fitted onto the nominal.
enum class FitMethod {
  least_squares,  ///< minimise the sum of the squared deviations
  minimum_zone,   ///< Chebyshev: minimise the largest |deviation|
  weighted,       ///< least squares with a weight per zone (FitOptions::weights)
};

/// The fit's degrees of freedom.
enum class FitFreedom {
  none,               ///< no move: the deviations as measured
  translation,        ///< translation in the plane
  translation_along,  ///< translation along FitOptions::direction only
  rotation,           ///< rotation about FitOptions::center only
  all,                ///< rotation and translation
};

/// The profile's zones, in the order of ZoneResult arrays.
enum class Zone : int { whole = 0, leading_edge = 1, trailing_edge = 2, pressure = 3, suction = 4 };
inline constexpr int zone_count = 5;

/// A zone's name: "whole", "le", "te", "pressure", "suction" ("unknown" for another value).
const char* zone_name(Zone zone);

/// Options of the fit (lengths in the profile's units).
struct FitOptions {
  FitMethod method = FitMethod::least_squares;  ///< see FitMethod
  FitFreedom freedom = FitFreedom::all;         ///< see FitFreedom
  /// translation_along: the direction in the plane (any length but 0).
  Eigen::Vector2d direction{1, 0};
  /// rotation: the centre in the plane; NaN = the nominal's area centroid.
  Eigen::Vector2d center{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  /// compare_blade, translation_along: the direction in 3D (its part across the planes).
  Eigen::Vector3d direction_3d{1, 0, 0};
  /// compare_blade, rotation: a point of the axis (parallel to the planes' normal) in 3D;
  /// NaN = the mean of the sections' nominal centroids.
  Eigen::Vector3d center_3d{std::numeric_limits<double>::quiet_NaN(), 0, 0};
  /// weighted: the weight of a point in each zone (index: Zone; `whole` is not used).
  std::array<double, zone_count> weights{1, 1, 1, 1, 1};
  int max_iterations = 200;   ///< fit iterations at most
  double convergence = 1e-9;  ///< length: the fit stops when a step moves no point by more
};

/// Options of compare_section and compare_blade.
struct CompareOptions {
  FitOptions fit;           ///< the best fit
  double edge_zone = 0.05;  ///< edge zones: the profile from each edge point to this fraction of the chord
  double hole = 0;  ///< length: a stretch of nominal longer than this without a point is a hole; 0 = auto
  double hole_spacings = 10;  ///< hole = 0: this many median spacings of the points along the nominal,
  double hole_floor = 0.25;   ///< ... and at least this length
  double outlier_distance =
      0;  ///< length: isolated points farther off are left out; 0 = automatic, < 0 = none
  double outlier_floor = 0.02;  ///< length: least automatic outlier distance (6 noise sigmas otherwise)
};

/// The nominal profile of a section, in the measured section's plane coordinates.
struct NominalSection {
  BSpline curve;                   ///< closed nominal profile
  Eigen::Vector2d le_point{0, 0};  ///< its leading-edge point (SectionParams::le_point)
  Eigen::Vector2d te_point{0, 0};  ///< its trailing-edge point
  int pressure_side = -1;          ///< +1: the pressure side lies left of LE -> TE, -1 right (CamberResult)
};

/// A rigid motion of the plane: p -> R(angle) p + translation.
struct Motion2 {
  double angle = 0;                   ///< degrees, counterclockwise
  Eigen::Vector2d translation{0, 0};  ///< length
  /// The moved point.
  Eigen::Vector2d apply(const Eigen::Vector2d& p) const;
};

/// What the fit did.
struct FitResult {
  Motion2 motion;         ///< moves the measured points onto the nominal
  int iterations = 0;     ///< fit iterations done
  bool converged = true;  ///< false when max_iterations ran out first
  double rms_before = 0;  ///< rms deviation of the points (outliers out) before the fit
  double max_before = 0;  ///< their largest |deviation| before
  double rms_after = 0;   ///< rms after
  double max_after = 0;   ///< largest |deviation| after
};

/// One measured point against the nominal.
struct PointDeviation {
  Eigen::Vector2d point{0, 0};   ///< the point moved by the fit
  Eigen::Vector2d foot{0, 0};    ///< its foot on the nominal (nearest nominal point)
  Eigen::Vector2d normal{0, 0};  ///< the nominal's outward unit normal there
  double t = 0;                  ///< nominal curve parameter of the foot
  double before = 0;             ///< signed deviation before the fit: positive = material outside
  double after = 0;              ///< signed deviation after the fit
  Zone zone = Zone::whole;       ///< the zone of the foot (never `whole`)
  bool outlier = false;          ///< left out of the fit and the zones
};

/// One zone's deviations after the fit.
struct ZoneResult {
  int points = 0;         ///< points in the zone (outliers out)
  double min = 0;         ///< smallest deviation (0 without points)
  double max = 0;         ///< largest deviation
  double form = 0;        ///< max - min: the narrowest band of constant width about the nominal holding them
  double length = 0;      ///< the zone's length along the nominal
  double unmeasured = 0;  ///< its longest stretch without a point
  bool measured = false;  ///< points and no hole in it (unmeasured <= the hole length)
};

/// A measured section against its nominal.
struct SectionComparison {
  FitResult fit;                             ///< the best fit
  std::vector<PointDeviation> points;        ///< one per measured point, in input order
  std::array<ZoneResult, zone_count> zones;  ///< index: Zone
  double hole = 0;                           ///< the hole length used
  double outlier_distance = 0;               ///< the outlier distance used (0: none left out)
  int outliers = 0;                          ///< points left out
};

/// Compares the measured points of a section with its nominal: the best fit (options.fit),
/// the deviations and the zones. Lengths in the profile's units. Throws section::Error
/// (`compare: ...`) with fewer points than the fit's degrees of freedom + 1, a nominal that
/// is not a closed curve, edge points that do not leave room for the sides, or bad options.
SectionComparison compare_section(const NominalSection& nominal, const std::vector<Eigen::Vector2d>& measured,
                                  const CompareOptions& options = {});

namespace compare {
struct Prepared;  // src/compare_steps.h
}

/// A nominal prepared once for many measured sections (blade after blade of one design):
/// its arc length, zones and the search structure of the points' feet, built by
/// prepare_nominal instead of by every compare_section call. Read only once prepared, so
/// that concurrent compare_section calls may share one; copies share it too.
struct PreparedNominal {
  std::shared_ptr<const compare::Prepared> prepared;  ///< what prepare_nominal built (null before)
  double edge_zone = 0;                               ///< CompareOptions::edge_zone it was built for
};

/// Prepares `nominal` for compare_section with `options` (only edge_zone matters). Throws
/// section::Error as compare_section does for a nominal that is not a closed curve or edge
/// points that leave no room for the sides, or bad options.
PreparedNominal prepare_nominal(const NominalSection& nominal, const CompareOptions& options = {});

/// compare_section on a prepared nominal: the same results, without preparing it again
/// (docs/PERFORMANCE.md, "compare"). Throws section::Error as compare_section does, and when
/// `nominal` was not prepared or was prepared for another edge zone.
SectionComparison compare_section(const PreparedNominal& nominal,
                                  const std::vector<Eigen::Vector2d>& measured,
                                  const CompareOptions& options = {});

/// One section of a blade for compare_blade.
struct ComparedSection {
  const NominalSection* nominal = nullptr;                 ///< its nominal, in the plane's coordinates
  const std::vector<Eigen::Vector2d>* measured = nullptr;  ///< its measured points
  Frame frame;                                             ///< its plane
};

/// A blade's sections fitted with one rigid motion.
struct BladeComparison {
  std::vector<SectionComparison> sections;  ///< per section: its part of the motion, deviations, zones
  Eigen::Vector3d axis{0, 0, 1};            ///< the rotation axis's direction (the planes' normal)
  double angle = 0;                         ///< degrees about it
  Eigen::Vector3d translation{0, 0, 0};     ///< x -> R x + translation moves the measured blade
  FitResult fit;                            ///< the fit over all the sections' points
};

/// Fits every section at once with one rigid motion: a rotation about an axis along the
/// planes' (common) normal and a translation across it, as options.fit.freedom allows
/// (translation_along and rotation read direction_3d and center_3d). Throws section::Error
/// when the planes are not parallel, and as compare_section does.
BladeComparison compare_blade(const std::vector<ComparedSection>& sections,
                              const CompareOptions& options = {});

/// The verdict of a value against its tolerance.
enum class Verdict : int {
  pass = 0,          ///< within its limits (by more than its uncertainty)
  fail = 1,          ///< outside its limits (by more than its uncertainty)
  not_measured = 2,  ///< a hole over what it rests on, or its section could not be compared
  uncertain = 3,     ///< measured, but the measurement cannot decide: a limit lies within its
                     ///< uncertainty, or camber flagged the value
};

/// How a value's measurement uncertainty enters its verdict (docs/COMPARE.md).
enum class DecisionRule {
  guarded,  ///< ISO 14253-1: pass and fail only when proven (value +- U on one side of each limit)
  simple,   ///< by the value alone, its uncertainty ignored
};

/// A tolerance on one value: limits on its deviation from the nominal (or on the value).
struct Tolerance {
  std::string item;                                       ///< what it applies to (docs/COMPARE.md)
  int section = -1;                                       ///< the section; -1 every section
  double low = -std::numeric_limits<double>::infinity();  ///< lowest allowed
  double high = std::numeric_limits<double>::infinity();  ///< highest allowed
  bool on_value = false;  ///< the limits bound the value itself, not its deviation from the nominal
  std::string where;      ///< where it was read (FILE:LINE), for messages
};

/// The verdict on values ranging from `lowest` to `highest` (one value: both the same), each
/// known to +- `uncertainty` (an expanded uncertainty U >= 0; 0: exact): fail when any lies
/// outside [low - U, high + U]; else not measured when `measured` is false or a value is
/// NaN; else uncertain when any lies outside [low + U, high - U]; else pass. A hole is
/// never a pass; with U = 0 no value is uncertain. Throws section::Error for limits that are
/// not numbers or not in order, or a negative uncertainty.
Verdict verdict(const Tolerance& tolerance, double lowest, double highest, bool measured,
                double uncertainty = 0);

/// The tolerance of `item` for `section`: the row naming the section, else the row for
/// every section, else nullptr.
const Tolerance* find_tolerance(const std::vector<Tolerance>& tolerances, const std::string& item,
                                int section);

}  // namespace section
