// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the stream's schema: docs/FORMAT.md lists every table and column as the schema
// declares them, and the stages write the tables the schema declares.
#include "section/edge.h"
#include "section/extras/generate.h"
#include "section/fit_spline.h"
#include "section/io/file.h"
#include "section/pipe/camber_stream.h"
#include "section/pipe/compare_stream.h"
#include "section/pipe/fit_spline_stream.h"
#include "section/pipe/schema.h"
#include "section/revolution.h"
#include "section/pipe/smooth_stream.h"

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

// A table as FORMAT.md documents it: `### NAME`, `Written by TOOL: MEANING`, then the rows
// of its `| column | unit | meaning |` table.
struct Documented {
  std::string name, written_by, meaning;
  std::vector<std::vector<std::string>> columns;  // name, unit, meaning
};

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(' '), b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// The cells of a markdown table row `| a | b | c |`.
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line.substr(1));
  std::string cell;
  while (std::getline(in, cell, '|')) out.push_back(trimmed(cell));
  return out;
}

// The tables of FORMAT.md's "## Tables" section, and its line "Edge shapes ...: LIST".
std::vector<Documented> documented(const std::string& text, std::string& edge_shapes) {
  std::vector<Documented> out;
  std::stringstream in(text);
  std::string line;
  bool tables = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) tables = line == "## Tables";
    if (!tables) continue;
    if (line.rfind("### ", 0) == 0) {
      out.push_back({trimmed(line.substr(4)), "", "", {}});
    } else if (!out.empty() && line.rfind("Written by ", 0) == 0) {
      const auto colon = line.find(": ");
      out.back().written_by = line.substr(11, colon - 11);
      out.back().meaning = line.substr(colon + 2, line.size() - colon - 3);  // without the full stop
    } else if (!out.empty() && line.rfind("| ", 0) == 0) {
      const auto row = cells(line);
      if (row.size() == 3 && row[0] != "column" && row[0].find("---") == std::string::npos)
        out.back().columns.push_back(row);
    } else if (line.rfind("Edge shapes", 0) == 0) {
      edge_shapes = line.substr(line.find(": ") + 2);
    }
  }
  return out;
}

// FORMAT.md's text for one table of the schema.
std::string markdown(const section::schema::TableDoc& t) {
  std::string out = "### " + std::string(t.name) + "\n\nWritten by " + t.written_by + ": " + t.meaning +
                    ".\n\n| column | unit | meaning |\n|---|---|---|\n";
  for (const auto& c : t.columns)
    out += "| " + std::string(c.name) + " | " + c.unit + " | " + c.meaning + " |\n";
  return out;
}

// True when `d` documents `t` as the schema declares it.
bool documents(const Documented& d, const section::schema::TableDoc& t) {
  if (d.name != t.name || d.written_by != t.written_by || d.meaning != t.meaning ||
      d.columns.size() != t.columns.size())
    return false;
  for (std::size_t c = 0; c < t.columns.size(); ++c)
    if (d.columns[c] != std::vector<std::string>{t.columns[c].name, t.columns[c].unit, t.columns[c].meaning})
      return false;
  return true;
}

// The edge shapes as FORMAT.md lists them: "0 round, 1 blunt, 2 sharp."
std::string edge_shape_list() {
  std::string out;
  for (const auto& e : section::edge_shape_names)
    out += (out.empty() ? "" : ", ") + std::to_string(static_cast<int>(e.shape)) + " " + e.name;
  return out + ".";
}

}  // namespace

TEST_CASE("schema: docs/FORMAT.md lists every table and column as the schema declares them", "[schema]") {
  const std::string path = std::string(SECTION_SOURCE_DIR) + "/docs/FORMAT.md";
  std::string edge_shapes;
  const auto docs = documented(section::read_file(path), edge_shapes);
  const auto schema = section::schema::tables();
  // On a difference, the schema's text of the tables is left beside the test to copy from.
  bool same = docs.size() == schema.size();
  for (std::size_t k = 0; same && k < schema.size(); ++k) same = documents(docs[k], schema[k]);
  if (!same) {
    std::ofstream out("FORMAT.tables.md");
    for (const auto& t : schema) out << markdown(t) << "\n";
  }
  INFO("the schema's tables as FORMAT.md should list them: FORMAT.tables.md in the test's folder");
  REQUIRE(docs.size() == schema.size());
  for (std::size_t k = 0; k < schema.size(); ++k) {
    const auto& t = schema[k];
    const auto& d = docs[k];
    INFO("table " << k << ": " << t.name);
    CHECK(d.name == t.name);
    CHECK(d.written_by == t.written_by);
    CHECK(d.meaning == t.meaning);
    REQUIRE(d.columns.size() == t.columns.size());
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      INFO("column " << c << ": " << t.columns[c].name);
      CHECK(d.columns[c][0] == t.columns[c].name);
      CHECK(d.columns[c][1] == t.columns[c].unit);
      CHECK(d.columns[c][2] == t.columns[c].meaning);
    }
  }
  CHECK(edge_shapes == edge_shape_list());
}

TEST_CASE("schema: the stages write each table with the schema's columns", "[schema]") {
  namespace schema = section::schema;
  // One section: loop 0 a blade profile, 240 points of it.
  const section::SectionTruth truth = section::section_truth(section::design_family()[0], 2400);
  section::Stream stream;
  // On a cylinder: the frames table with every column, and the meridians table.
  section::put_frames(stream,
                      {{3, section::surface_frame(section::cylinder_surface({0, 0, -100}, {1, 0, 0}, 105))}});
  section::Table points = schema::points.table();
  for (std::size_t i = 0; i < truth.profile.size(); i += 10)
    schema::points.add(points, {3, 0, i / 10, truth.profile[i], truth.profile_normal[i], 0.0});
  stream.put(points);
  section::smooth_stream(stream);
  section::FitSplineOptions fit;
  fit.samples = 50;
  section::fit_spline_stream(stream, fit);
  section::camber_stream(stream);
  const section::Stream nominal = stream;  // compare's tables: the section against itself
  section::compare_stream(stream, nominal);
  INFO(stream.issues.size() << " issues, the first: "
                            << (stream.issues.empty() ? "" : stream.issues[0].message));
  std::size_t found = 0;
  for (const auto& doc : schema::tables()) {
    const section::Table* t = stream.find(doc.name);
    if (!t) continue;
    ++found;
    INFO("table " << doc.name);
    std::vector<std::string> names;  // a point's columns are documented together: "le_x, le_y, le_z"
    for (const auto& c : doc.columns) {
      std::stringstream list(c.name);
      for (std::string n; std::getline(list >> std::ws, n, ',');) names.push_back(n);
    }
    CHECK(t->columns == names);
    if (std::string(doc.name) != "gaps") CHECK(t->rows() > 0);  // the profile has no hole
  }
  // All but slice's loops and skeleton, blade's two, and walls and wall_map (a solid section has
  // no cavity: tests/test_cavity.cpp writes them).
  CHECK(found == schema::tables().size() - 6);
  CHECK(schema::params.find(stream)->rows() == 1);
}

TEST_CASE("schema: a plain profile's splines table ends at the fit's iterations", "[schema]") {
  const section::SectionTruth truth = section::section_truth(section::design_family()[0], 400);
  const auto fit = section::fit_spline(truth.profile, truth.profile);
  const section::Stream stream = section::profile_stream(fit.spline, fit.rms);
  const auto& columns = section::schema::splines.get(stream).columns;
  REQUIRE(columns.size() == 9);
  CHECK(columns.front() == "section");
  CHECK(columns.back() == "iterations");
  CHECK(section::splines(stream).at({0, 0}).control.size() == fit.spline.control.size());
}
