// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/pipe/nominal_file.h"

#include "section/error.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/io/mesh_io.h"
#include "section/pipe/schema.h"

namespace section {

namespace {

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

// Runs `read`; an error that does not name `path` gets it in front, as the tools name
// the file an error comes from.
template <class Read>
void naming(const std::string& path, Read&& read) {
  try {
    read();
  } catch (const Error& e) {
    const std::string name = path == "-" ? "<stdin>" : path;
    if (std::string(e.what()).find(name) != std::string::npos) throw;
    throw Error(name + ": " + e.what());
  }
}

}  // namespace

NominalSource NominalFile::source() const {
  NominalSource s;
  s.name = name;
  if (kind == Kind::mesh) s.mesh = &mesh;
  if (kind == Kind::stream) s.stream = &stream;
  if (kind == Kind::points) s.points = &points;
  return s;
}

NominalFile read_nominal(const std::string& path, const std::string& units) {
  NominalFile n;
  n.name = path;
  for (const char* ext : {".stl", ".obj", ".off", ".ply", ".STL", ".OBJ", ".OFF", ".PLY"})
    if (ends_with(path, ext)) {
      n.mesh = read_mesh(path);
      n.kind = NominalFile::Kind::mesh;
      n.units = nominal_to_mm(&n.mesh, nullptr, units);
      return n;
    }
  const std::string text = read_file(path);
  naming(path, [&] {
    if (text.rfind("# libsection-stream", 0) == 0) {
      if (!units.empty()) throw Error("--nominal-units: a stream says its own unit (# units)");
      n.stream = parse_stream(text, path);
      convert_to_mm(n.stream);
      n.kind = NominalFile::Kind::stream;
    } else {
      n.points = parse_csv(text, path);
      n.kind = NominalFile::Kind::points;
      n.units = nominal_to_mm(nullptr, &n.points, units);
    }
  });
  return n;
}

}  // namespace section
