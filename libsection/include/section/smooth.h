// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file smooth.h
/// Energy-minimising smoothing of an ordered section polyline (Li et al. 2014, sec. 2.3).
///
/// The smoothed points q_i minimise E = a * E_C + b * E_S over the measured points q0_i:
///   E_C = 1/2 sum_i kappa_i^2 (l_i + l_{i+1}) / 2,
///   kappa_i = 2 / (l_i + l_{i+1}) * |(q_{i+1} - q_i) / l_{i+1} - (q_i - q_{i-1}) / l_i|,
///   E_S = sum_i |q_i - q0_i|^2,            l_i = |q_i - q_{i-1}|.
/// Each outer iteration freezes the lengths l_i, solves the linear system grad E = 0 (cyclic
/// pentadiagonal, the same for u and v) and updates the lengths. `a` depends on the units
/// and the spacing: `smoothing_length` sets it scale-free (docs/SMOOTH.md).
#include <Eigen/Core>

#include <string>
#include <vector>

namespace section {

/// How each outer iteration solves its linear system.
enum class SmoothSolver {
  cholmod,      ///< global sparse Cholesky (CHOLMOD), one factorisation per outer iteration
  gauss_seidel  ///< the paper's point-by-point Gauss-Seidel sweeps on the same system
};

/// Parses "cholmod" or "gauss-seidel" / "gauss_seidel"; throws section::Error otherwise.
SmoothSolver parse_smooth_solver(const std::string& name);

/// Options of smooth and smooth_stream (docs/SMOOTH.md: strength, stopping rules).
struct SmoothOptions {
  double smoothing_length = 0;  ///< curve units: a wiggle this long keeps half its amplitude; 0 = `a`
  double a = 0;                 ///< length^3: weight of E_C when smoothing_length is 0; 0 = relative_length
  double relative_length = 6;   ///< mean spacings: the smoothing length when smoothing_length and a are 0
  double b = 1.0;               ///< weight of the closeness energy E_S (paper: 1-1.2)
  SmoothSolver solver = SmoothSolver::cholmod;  ///< linear solver of each outer iteration
  int max_iterations = 20;                      ///< cap on outer iterations (length updates)
  double tolerance = 1e-9;                      ///< stop when |E_k - E_{k-1}| <= tolerance * E_k
  /// Mean spacings: stop when no point moved farther across the curve in the last iteration.
  /// 0.006 spacing: on scans the later iterations only creep (docs/SMOOTH.md, issue 25).
  double move_tolerance = 6e-3;
  double merge_distance = 1e-3;    ///< mean spacings: closer consecutive points are merged
  bool closed = true;              ///< the polyline is a closed loop (last point joins the first)
  int max_sweeps = 1000000;        ///< gauss_seidel only: cap on sweeps per outer iteration
  double sweep_tolerance = 1e-12;  ///< gauss_seidel only: least update, times the curve's size
  int threads = 0;                 ///< stream stage: worker threads over the loops; 0 = all cores
};

/// What smooth returns: the smoothed points and the energy diagnostics.
struct SmoothResult {
  std::vector<Eigen::Vector2d> points;  ///< smoothed points, same order as the input (after merging)
  double energy_before = 0;             ///< E of the input (after merging): a * E_C, since E_S = 0
  double energy_after = 0;              ///< E of the result
  int iterations = 0;                   ///< outer iterations done
  int sweeps = 0;                       ///< gauss_seidel only: sweeps done over all outer iterations
  std::vector<double> energy_history;   ///< E after each outer iteration, energy_before first
  double rms_move = 0;                  ///< RMS distance from input (after merging) to smoothed points
  double max_move = 0;                  ///< largest distance between an input and its smoothed point
  int repaired = 0;                     ///< input points merged away (duplicates) or dropped (lone spikes)
  double a = 0;                         ///< the curvature weight actually used
  double spacing = 0;                   ///< mean distance between consecutive input points (after merging)
  bool converged = false;               ///< a tolerance was met, or no step lowers E, before max_iterations
};

/// Smooths one ordered polyline (closed or open) by minimising E above; coordinates in any
/// length unit. The curvature weight is, in order: from smoothing_length if > 0, a if > 0,
/// else from relative_length * mean spacing. Needs at least 5 points after merging
/// duplicates. Throws section::Error (`smooth: ...`) on fewer points, non-finite
/// coordinates or bad options.
SmoothResult smooth(const std::vector<Eigen::Vector2d>& points, const SmoothOptions& options = {});

/// The energy E = a E_C + b E_S of `points` against `reference` (same size), as defined
/// above. A zero-length segment counts with a zero tangent (the result stays finite).
double smooth_energy(const std::vector<Eigen::Vector2d>& points,
                     const std::vector<Eigen::Vector2d>& reference, double a, double b, bool closed = true);

/// The curvature weight a that gives a smoothing (half-amplitude) wavelength `length` at
/// mean point spacing `spacing`: a = 2 b (length / 2 pi)^4 / spacing.
double smoothing_weight(double length, double spacing, double b = 1.0);

/// The inverse: the half-amplitude wavelength of weight a at that spacing.
double smoothing_length(double a, double spacing, double b = 1.0);

}  // namespace section
