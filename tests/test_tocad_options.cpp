// SPDX-License-Identifier: GPL-3.0-or-later
// tocad's command line without the binary (tools/args/tocad_args.h): the format from the
// flag or the output's extension, and usage errors (exit code 2) when neither gives one.
#if __has_include("args/tocad_args.h")  // the tools are built (SECTION_BUILD_TOOLS)
#include "args/tocad_args.h"

#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace {

using section::tool::TocadArgs;

struct Parsed {
  TocadArgs args;
  int code = 0;
  std::string err;
};

Parsed parsed(std::vector<std::string> words) {
  words.insert(words.begin(), TocadArgs::name);
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  Parsed p;
  std::ostringstream out, err;
  p.code = section::tool::parse(static_cast<int>(argv.size()), argv.data(), p.args, out, err);
  p.err = err.str();
  return p;
}

}  // namespace

TEST_CASE("tool options: tocad takes its format from the flag or the output's extension", "[tools]") {
  CHECK(parsed({"s.csv", "-o", "blade.DXF"}).args.format == "dxf");
  CHECK(parsed({"s.csv", "-o", "dir.v2/blade.igs"}).args.format == "iges");
  CHECK(parsed({"s.csv", "-o", "blade.iges"}).args.format == "iges");
  CHECK(parsed({"s.csv", "-o", "p.json"}).args.format == "json");
  const auto p = parsed({"s.csv", "--format", "iges", "-o", "blade.dxf", "--polyline-tolerance", "0.01",
                         "--profiles-only", "--tables", "params,camber"});
  REQUIRE(p.code == -1);
  CHECK(p.args.format == "iges");
  CHECK(p.args.polyline_tolerance == 0.01);
  CHECK(p.args.profiles_only);
  CHECK(p.args.tables == std::vector<std::string>{"params", "camber"});
  CHECK(section::tool::format_of("dir.v2/blade") == "");
  for (const auto& bad : std::vector<std::vector<std::string>>{{"s.csv"},
                                                               {"s.csv", "-o", "b.step"},
                                                               {"--format", "step"},
                                                               {"-f", "json", "--tables", "nothing"},
                                                               {"-f", "dxf", "--polyline-tolerance", "-1"}}) {
    const auto q = parsed(bad);
    INFO(bad.size() << " words: " << q.err);
    CHECK(q.code == 2);
    CHECK(q.err.rfind("tocad: usage error:", 0) == 0);
  }
}
#endif
