// SPDX-License-Identifier: GPL-3.0-or-later
// tocad: the sections of a pipe stream as CAD curves (DXF, IGES) or as JSON.
#include "args/tocad_args.h"

#include "section/error.h"
#include "section/io/cad.h"
#include "section/io/file.h"
#include "section/io/json.h"
#include "section/io/stream.h"
#include "section/pipe/cad_stream.h"
#include "section/pipe/schema.h"

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <set>

namespace {

using section::tool::TocadArgs;

// The IGES file's date: now (UTC), or SOURCE_DATE_EPOCH for a reproducible file.
std::string timestamp() {
  std::time_t now = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) now = static_cast<std::time_t>(std::atoll(epoch));
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%d.%H%M%S", &utc);
  return buf;
}

// Sections named in issues that have no curve.
void warn_missing(const section::Stream& stream, const std::vector<section::CadCurve>& curves) {
  std::set<int> have;
  for (const auto& c : curves) have.insert(c.section);
  for (const auto& i : stream.issues)
    if (!have.count(i.section) && i.loop <= 0)
      std::cerr << "tocad: warning: section " << i.section << " has no curve (" << i.stage << ": "
                << i.message << ")\n";
}

// The stream's curves and the options they are written with; throws when it has none.
std::vector<section::CadCurve> curves_of(const TocadArgs& a, const section::Stream& stream,
                                         section::CadOptions& o) {
  std::vector<section::CadCurve> curves = section::cad_curves(stream, !a.profiles_only);
  warn_missing(stream, curves);
  if (curves.empty()) throw section::Error("the stream has no fitted curve (every section failed?)");
  o.polyline_tolerance = a.polyline_tolerance;
  o.source = section::tool::input_name(a.common.input);
  o.timestamp = timestamp();
  return curves;
}

std::string json_file(const TocadArgs& a, const section::Stream& stream) {
  std::vector<const section::Table*> tables;
  const std::vector<section::schema::TableDoc> known = section::schema::tables();
  for (const auto& name : a.tables) {
    const auto doc = std::find_if(known.begin(), known.end(), [&](const auto& d) { return name == d.name; });
    tables.push_back(&stream.get(name, doc == known.end() ? "?" : doc->written_by));
  }
  if (!a.tables_given)
    if (const section::Table* walls = section::schema::walls.find(stream)) tables.push_back(walls);
  return section::format_json(stream, tables);
}

void run_tocad(const TocadArgs& a) {
  std::string text;
  section::CadOptions o;
  std::vector<section::CadCurve> curves;
  section::tool::with_input(a.common.input, [&] {
    section::Stream stream = section::read_stream(a.common.input);
    section::convert_to_mm(stream);
    if (a.format == "json") {
      text = json_file(a, stream);
    } else {
      curves = curves_of(a, stream, o);
      if (a.format == "iges") text = section::format_iges(curves, o);
    }
  });
  // DXF: written a curve at a time (its text is never whole), after every check of the
  // curves (their errors name the input: CadOptions::source).
  if (a.format == "dxf")
    section::write_dxf(a.common.output, curves, o);
  else
    section::write_file(a.common.output, text);
}

}  // namespace

int main(int argc, char** argv) {
  return section::tool::run<TocadArgs>(argc, argv, [&](const TocadArgs& args) { run_tocad(args); });
}
