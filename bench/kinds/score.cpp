// SPDX-License-Identifier: GPL-3.0-or-later
// evaluate_kinds (evaluate_kinds.cpp): the quantities scored, reading what the pipe wrote
// (params CSV, flags, frames) and scoring one section against the truth.
#include "kinds.h"
#include "section/checks.h"
#include "section/io/file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>

using namespace section;

namespace kind_score {

// The quantities scored, their targets and the words that flag them.
const Quantity quantities[nq] = {
    {"camber rms", "um", 3, {"camber line"}, {"camber", "camber_line"}},
    {"camber max", "um", 15, {"camber line"}, {"camber", "camber_line"}},
    {"chord", "um", 10, {"chord"}, {"chord", "caliper_chord"}},
    {"stagger", "deg", 0.5, {"stagger"}, {"stagger"}},
    {"max thickness", "um", 5, {"thickness"}, {"max_thickness", "thickness"}},
    {"LE radius", "%", 3, {"leading edge", "le radius"}, {"le_radius", "le", "edge_radius", "edges"}},
    {"TE radius", "%", 10, {"trailing edge", "te radius"}, {"te_radius", "te", "edge_radius", "edges"}},
    {"inlet angle", "deg", 0.5, {"inlet", "metal angle"}, {"inlet_angle", "metal_angles", "angles"}},
    {"outlet angle", "deg", 0.5, {"outlet", "metal angle"}, {"outlet_angle", "metal_angles", "angles"}},
    {"camber angle", "deg", 0.5, {"camber angle", "metal angle"}, {"camber_angle", "metal_angles", "angles"}},
    {"LE point", "um", 15, {"leading edge", "edge point"}, {"le_point", "edge_points", "le"}},
    {"TE point", "um", 15, {"trailing edge", "edge point"}, {"te_point", "edge_points", "te"}},
};

// ---------------------------------------------------------------------------------------
// Reading what the pipe wrote.

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, sep)) cells.push_back(cell);
  return cells;
}

Csv read_csv(const std::string& path) {
  Csv csv;
  std::istringstream in(read_file(path));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (csv.header.empty())
      csv.header = split(line, ',');
    else
      csv.rows.push_back(split(line, ','));
  }
  return csv;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool SectionFlags::names(Q q) const {
  if (row_flag) return true;
  for (const char* w : quantities[q].issue_words)
    if (issues.find(w) != std::string::npos) return true;
  for (const char* w : quantities[q].flag_words)
    if (tokens.count(w)) return true;
  return false;
}

SectionFlags flags_of(const Stream& stream, const Csv& params, std::size_t row, int section) {
  SectionFlags f;
  for (const auto& is : stream.issues)
    if (is.section == section) f.issues += lower(is.stage + ": " + is.message) + "; ";
  const long c = params.column("flags");
  if (c < 0 || std::size_t(c) >= params.rows[row].size()) return f;
  const std::string cell = lower(params.rows[row][std::size_t(c)]);
  char* end = nullptr;
  const double number = std::strtod(cell.c_str(), &end);
  if (!cell.empty() && end && *end == '\0') {
    // Each set bit flags its check's columns; "every ..." (a doubtful unit) the whole row.
    const auto mask = section::flags_mask(number);
    for (const auto& check : section::check_names) {
      if (!(mask & section::bit(check.check))) continue;
      if (std::string(check.columns).rfind("every", 0) == 0) f.row_flag = true;
      std::istringstream words(check.columns);
      for (std::string column; words >> column;) f.tokens.insert(column);
    }
    return f;
  }
  std::string word;
  for (char ch : cell + " ") {
    if (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_') {
      word += ch;
    } else if (!word.empty()) {
      f.tokens.insert(word);
      word.clear();
    }
  }
  return f;
}

// ---------------------------------------------------------------------------------------
// Scoring one section.

std::map<int, Frame> frames_of(const Stream& stream) {
  std::map<int, Frame> frames;
  const Table* t = stream.find("frames");
  if (!t) return frames;
  auto vec = [&](std::size_t r, const std::string& p) {
    return Eigen::Vector3d(t->at(r, t->column(p + "_x")), t->at(r, t->column(p + "_y")),
                           t->at(r, t->column(p + "_z")));
  };
  for (std::size_t r = 0; r < t->rows(); ++r)
    frames[int(t->at(r, 0))] = {vec(r, "origin"), vec(r, "u"), vec(r, "v"), vec(r, "n")};
  return frames;
}

// The errors of one params row (lengths scaled by `mm` to mm) against the truth.
std::array<Value, nq> score_row(const Csv& params, std::size_t row, const Frame& frame, const Stream& stream,
                                int section, double mm, const SectionTruth& t, bool dense) {
  auto get = [&](const char* c) {
    const long i = params.column(c);
    return i < 0 ? NAN : std::strtod(params.rows[row][std::size_t(i)].c_str(), nullptr);
  };
  std::array<Value, nq> v;
  const double chord_um = 1e3 * t.chord, angle = dense ? 0.5 : 1;
  double sum = 0, worst = 0;
  int count = 0;
  if (const Table* cam = stream.find("camber"))
    for (std::size_t r = 0; r < cam->rows(); ++r)
      if (int(cam->at(r, 0)) == section) {
        const Eigen::Vector2d p(cam->at(r, cam->column("x")) * mm, cam->at(r, cam->column("y")) * mm);
        const double d = camber_distance(t, p);
        sum += d * d, worst = std::max(worst, d), ++count;
      }
  v[cam_rms] = {count ? 1e3 * std::sqrt(sum / count) : NAN, dense ? 3 : 0.02 * chord_um};
  v[cam_max] = {count ? 1e3 * worst : NAN, dense ? 15 : 0.02 * chord_um};
  v[chord] = {1e3 * (get("chord") * mm - t.chord), dense ? 10 : 0.02 * chord_um};
  const Eigen::Vector2d le(get("le_x") * mm, get("le_y") * mm), te(get("te_x") * mm, get("te_y") * mm);
  const Eigen::Vector2d ch = te - le;
  v[stagger] = {wrap_degrees(std::atan2(ch.y(), ch.x()) * 180 / M_PI - t.stagger), angle};
  v[tmax] = {1e3 * (get("max_thickness") * mm - t.max_thickness), dense ? 5 : 20 * t.max_thickness};
  auto radius = [&](double measured, double truth, double target) {
    if (truth > 0) return Value{100 * (measured * mm / truth - 1), dense ? target : 2};
    return Value{1e3 * measured * mm, dense ? sharp_allowance_um : sharp_allowance_sparse_um, true};
  };
  v[rle] = radius(get("le_radius"), t.le_radius, 3);
  v[rte] = radius(get("te_radius"), t.te_radius, 10);
  const double in = frame.xy_angle(get("inlet_angle")), out = frame.xy_angle(get("outlet_angle"));
  v[inlet] = {wrap_degrees(in - t.inlet_angle), angle};
  v[outlet] = {wrap_degrees(out - t.outlet_angle), angle};
  v[cam_angle] = {wrap_degrees(get("camber_angle") - (t.inlet_angle - t.outlet_angle)), angle};
  v[le_pt] = {1e3 * (le - t.le_point).norm(), dense ? 15 : 0.02 * chord_um};
  v[te_pt] = {1e3 * (te - t.te_point).norm(), dense ? 15 : 0.02 * chord_um};
  return v;
}
}  // namespace kind_score
