// SPDX-License-Identifier: GPL-3.0-or-later
// The rigid fits of compare over one section or many (a blade): least squares (weighted by
// zone or not) by Gauss-Newton on the point-to-tangent distances, and minimum zone by
// sequential linear programs in a trust region. Each step is composed exactly with the
// motion so far, and the feet are found again on the nominal after each.
#include "compare_steps.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>

namespace section::compare {

namespace {

Eigen::Vector2d rotated(double angle, const Eigen::Vector2d& p) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

// What a block holds of the motion, to put back after a rejected step.
struct Saved {
  double angle;
  Eigen::Vector2d translation;
  std::vector<Eigen::Vector2d> moved;
  fit::Feet feet;
};

std::vector<Saved> save(const std::vector<Block>& blocks) {
  std::vector<Saved> out;
  for (const Block& b : blocks) out.push_back({b.angle, b.translation, b.moved, b.feet});
  return out;
}

void restore(std::vector<Block>& blocks, std::vector<Saved>& saved) {
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    blocks[i].angle = saved[i].angle;
    blocks[i].translation = saved[i].translation;
    blocks[i].moved.swap(saved[i].moved);
    blocks[i].feet = std::move(saved[i].feet);
  }
}

// Composes the step x (fit parameters) with each block's motion and places the points;
// returns the largest move of a point it makes.
double move_by(std::vector<Block>& blocks, const Eigen::VectorXd& x) {
  double moved = 0;
  for (Block& b : blocks) {
    const Eigen::Vector3d local = b.map * x;
    b.angle += local(0);
    b.translation = rotated(local(0), b.translation - b.center) + b.center + local.tail<2>();
    double lever = 0;
    for (const auto& p : b.moved) lever = std::max(lever, (p - b.center).norm());
    moved = std::max(moved, std::abs(local(0)) * lever + local.tail<2>().norm());
    b.place();
  }
  return moved;
}

// Each point's gradient of its deviation in the fit parameters (rows), its deviation and
// its weight.
struct Linear {
  Eigen::MatrixXd g;
  Eigen::VectorXd r, w;
};

Linear linearise(const std::vector<Block>& blocks) {
  std::size_t n = 0;
  for (const Block& b : blocks) n += b.points.size();
  const Eigen::Index k = blocks.front().map.cols();
  Linear l{Eigen::MatrixXd(n, k), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  std::size_t row = 0;
  for (const Block& b : blocks)
    for (std::size_t i = 0; i < b.points.size(); ++i, ++row) {
      const Eigen::Vector2d nrm = b.nominal->normal_at(b.feet.t[i]);
      const Eigen::Vector2d arm = b.moved[i] - b.center;
      const Eigen::Vector3d local(nrm.dot(Eigen::Vector2d(-arm.y(), arm.x())), nrm.x(), nrm.y());
      l.g.row(row) = local.transpose() * b.map;
      l.r(row) = b.deviation(i);
      l.w(row) =
          b.zone_weight.empty() ? 1.0 : b.zone_weight[static_cast<int>(b.nominal->zone_at(b.feet.t[i]))];
    }
  return l;
}

double cost(const Linear& l) {
  return l.w.dot(l.r.cwiseProduct(l.r));
}

// The same sum over the blocks as placed, without the gradients.
double cost(const std::vector<Block>& blocks) {
  double sum = 0;
  for (const Block& b : blocks)
    for (std::size_t i = 0; i < b.points.size(); ++i) {
      const double w =
          b.zone_weight.empty() ? 1.0 : b.zone_weight[static_cast<int>(b.nominal->zone_at(b.feet.t[i]))];
      sum += w * b.deviation(i) * b.deviation(i);
    }
  return sum;
}

}  // namespace

void Block::place() {
  const double c = std::cos(angle), s = std::sin(angle);
  const std::size_t n = points.size();
  moved.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    moved[i] = Eigen::Vector2d(c * points[i].x() - s * points[i].y(), s * points[i].x() + c * points[i].y()) +
               translation;
  if (feet.t.size() != n && n >= 64) {
    // The first feet: points come in order along the profile (slice orders them), so the
    // full search of every 4th point seeds its neighbours' tracking; a point it does not
    // serve (unordered input) gets the full search too.
    constexpr std::size_t every = 4;
    std::vector<Eigen::Vector2d> some;
    for (std::size_t i = 0; i < n; i += every) some.push_back(moved[i]);
    const fit::Feet coarse = fit::foot_points(nominal->curve, nominal->pc, some, nullptr, &nominal->search);
    feet = fit::Feet{};
    feet.t.resize(n);
    feet.signed_distance.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      feet.t[i] = coarse.t[std::min((i + every / 2) / every, some.size() - 1)];
    for (std::size_t j : coarse.order)
      for (std::size_t i = j * every; i < std::min(n, (j + 1) * every); ++i) feet.order.push_back(i);
  }
  const bool track = feet.t.size() == n;
  feet = fit::foot_points(nominal->curve, nominal->pc, moved, track ? &feet : nullptr, &nominal->search);
}

std::array<double, 2> spread(const std::vector<Block>& blocks) {
  double largest = 0, sum = 0;
  std::size_t n = 0;
  for (const Block& b : blocks)
    for (std::size_t i = 0; i < b.points.size(); ++i, ++n) {
      const double d = b.deviation(i);
      largest = std::max(largest, std::abs(d));
      sum += d * d;
    }
  return {largest, n ? std::sqrt(sum / static_cast<double>(n)) : 0.0};
}

FitRun fit_least_squares(std::vector<Block>& blocks, const FitOptions& options) {
  FitRun run;
  if (blocks.empty() || blocks.front().map.cols() == 0) return run;
  run.converged = false;
  while (run.iterations < options.max_iterations) {
    ++run.iterations;
    const Linear l = linearise(blocks);
    const Eigen::MatrixXd h = l.g.transpose() * l.w.asDiagonal() * l.g;
    const Eigen::VectorXd rhs = -(l.g.transpose() * l.w.cwiseProduct(l.r));
    // A motion the points cannot tell (a rotation of a circle) is left at 0.
    const Eigen::VectorXd x = h.completeOrthogonalDecomposition().solve(rhs);
    const double before = cost(l);
    std::vector<Saved> saved = save(blocks);
    double step = 1, moved = 0;
    for (int halving = 0; halving < 30; ++halving, step *= 0.5) {
      moved = move_by(blocks, Eigen::VectorXd(step * x));
      if (cost(blocks) <= before * (1 + 1e-12) + 1e-300) break;
      std::vector<Saved> again = saved;
      restore(blocks, again);
    }
    if (moved <= options.convergence) {
      run.converged = true;
      break;
    }
  }
  return run;
}

FitRun fit_minimum_zone(std::vector<Block>& blocks, const FitOptions& options) {
  FitRun run;
  if (blocks.empty() || blocks.front().map.cols() == 0) return run;
  run.converged = false;
  double largest = spread(blocks)[0];
  // The parameters scaled to lengths (a rotation by its lever), so that one box bounds them.
  Linear l = linearise(blocks);
  Eigen::VectorXd scale(l.g.cols());
  for (Eigen::Index j = 0; j < l.g.cols(); ++j) scale(j) = std::max(l.g.col(j).cwiseAbs().maxCoeff(), 1e-300);
  double box = std::max(largest, 1e-9);
  const double smallest_box = 1e-14 * (1 + largest);
  while (run.iterations < options.max_iterations && box > smallest_box) {
    ++run.iterations;
    const Eigen::MatrixXd g = l.g * scale.cwiseInverse().asDiagonal();
    const MinimaxStep step = minimax_step(g, l.r, box);
    const double predicted = largest - step.z;
    if (predicted <= 1e-15 * (1 + largest)) {
      run.converged = true;
      break;
    }
    std::vector<Saved> saved = save(blocks);
    const Eigen::VectorXd x = step.x.cwiseQuotient(scale);
    const double moved = move_by(blocks, x);
    const double reached = spread(blocks)[0];
    const double ratio = (largest - reached) / predicted;
    if (reached < largest) {
      largest = reached;
      l = linearise(blocks);
      if (ratio > 0.75 && step.x.cwiseAbs().maxCoeff() > 0.99 * box) box *= 2;
      if (ratio < 0.25) box *= 0.5;
      if (moved <= options.convergence) {
        run.converged = true;
        break;
      }
    } else {
      restore(blocks, saved);
      box = 0.25 * std::min(box, step.x.cwiseAbs().maxCoeff());
    }
  }
  if (box <= smallest_box) run.converged = true;
  return run;
}

}  // namespace section::compare
