// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/error.h"
#include "section/io/stream.h"
#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/io/stream_reader.h"
#include "section/pipe/run_stage.h"
#include "section/pipe/schema.h"

#include "thrown.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>

using namespace section;

namespace {

// The message parse_stream refuses `text` with, or "no error".
std::string parse_error(const std::string& text, const std::string& source = "s.csv") {
  return thrown([&] { parse_stream(text, source); });
}

}  // namespace

TEST_CASE("pipe: a stream round-trips exactly, doubles included", "[pipe]") {
  Stream s;
  s.units = "mm";
  s.history = {"slice --count 3 blade.ply"};
  s.issues.push_back({2, -1, "slice", "no points in the slab"});
  Table t{"points", {"section", "loop", "index", "u", "v"}, {}};
  t.add_row({0, 0, 0, 0.1, -1.0 / 3.0});
  t.add_row({0, 0, 1, 1e-300, std::nextafter(1.0, 2.0)});
  s.put(t);
  put_frames(s, {{0, make_frame({1, 2, 3}, {0, 0, 2})}});
  const Stream r = parse_stream(format_stream(s), "mem");
  REQUIRE(r.units == "mm");
  REQUIRE(r.history == s.history);
  REQUIRE(r.issues.size() == 1);
  CHECK(r.issues[0].section == 2);
  CHECK(r.issues[0].message == "no points in the slab");
  const Table& p = r.get("points", "slice");
  REQUIRE(p.values == t.values);  // bit-exact
  const auto f = frames(r);
  REQUIRE(f.size() == 1);
  CHECK((f.at(0).origin - Eigen::Vector3d(1, 2, 3)).norm() == 0);
  CHECK((f.at(0).n - Eigen::Vector3d(0, 0, 1)).norm() < 1e-15);
}

TEST_CASE("pipe: malformed streams name the line", "[pipe]") {
  const std::string head = "# libsection-stream 1\n# table points\nsection,u,v\n";
  const auto message = [](const std::string& text) { return parse_error(text); };
  CHECK_THAT(message(""), Catch::Contains("empty"));
  CHECK_THAT(message("x,y\n1,2\n"), Catch::Contains("s.csv:1") && Catch::Contains("not a libsection stream"));
  CHECK_THAT(message("# libsection-stream 7\n"), Catch::Contains("version"));
  CHECK_THAT(message(head + "0,1,abc\n"), Catch::Contains("s.csv:4") && Catch::Contains("'abc'"));
  CHECK_THAT(message(head + "0,1\n"), Catch::Contains("s.csv:4") && Catch::Contains("truncated"));
  CHECK_THAT(message(head + "0,1,2,3\n"), Catch::Contains("s.csv:4"));
  CHECK_THAT(message(head + "0,nan,2\n"), Catch::Contains("non-finite"));
  CHECK_THAT(message("# libsection-stream 1\n1,2,3\n"), Catch::Contains("outside any table"));
  CHECK_THAT(message("# libsection-stream 1\n# table t\n"), Catch::Contains("no header"));
}

TEST_CASE("pipe: large tables (parsed and formatted in pieces) round-trip and name bad lines", "[pipe]") {
  // 60000 rows of 7 cells: well above the block size that is split over the cores.
  Stream s;
  Table t{"points", {"section", "loop", "index", "u", "v", "nu", "nv"}, {}};
  const double specials[] = {-0.0, 99999, -99999, 100000, -100000, 1e-7, 123456789, 0.5, -1.0 / 3.0, 1e14};
  for (int i = 0; i < 60000; ++i)
    t.add_row({double(i / 3000), 0, double(i % 3000), specials[i % 10] + (i % 7 == 0 ? 0 : i * 1e-3),
               std::sin(i * 0.001), specials[(i + 3) % 10], std::cos(i * 0.001)});
  s.put(t);
  const std::string text = format_stream(s);
  REQUIRE(text.size() > (std::size_t(1) << 18));
  const Stream r = parse_stream(text, "big");
  REQUIRE(r.get("points", "slice").values.size() == t.values.size());
  CHECK(r.get("points", "slice").values == t.values);
  CHECK(format_stream(r) == text);  // the same text again, -0 included
  // Every number is written as format_number writes it.
  const std::size_t first_row = text.find('\n', text.find("section,loop")) + 1;
  const std::string row = text.substr(first_row, text.find('\n', first_row) - first_row);
  std::string expected;
  for (std::size_t c = 0; c < 7; ++c) expected += (c ? "," : "") + format_number(t.values[c]);
  CHECK(row == expected);
  // A bad cell deep in the block: the message names its line as the serial parse does.
  const auto message = [](const std::string& bad) { return parse_error(bad, "big.csv"); };
  std::string bad = text;
  std::size_t at = 0;
  for (int line = 1; line < 45003; ++line) at = bad.find('\n', at) + 1;  // start of line 45003
  bad.insert(at, "x");
  CHECK_THAT(message(bad), Catch::Contains("big.csv:45003:"));
  bad = text;
  bad.insert(bad.find('\n', at), ",7");
  CHECK_THAT(message(bad), Catch::Contains("big.csv:45003:") && Catch::Contains("more values"));
  // The last line without its newline still counts.
  const Stream cut = parse_stream(text.substr(0, text.size() - 1), "big");
  CHECK(cut.get("points", "slice").values == t.values);
}

TEST_CASE("pipe: a table passed through is written back as it was read, a changed one formatted", "[pipe]") {
  // Rows in a form this library does not write ("1.50", "+2", "3e0"): kept as they came
  // while the table is unchanged, shortest form once it changes.
  std::string rows;
  for (int i = 0; i < 30000; ++i) rows += std::to_string(i) + ",1.50,+2,3e0\n";
  const std::string text =
      "# libsection-stream 1\n# units mm\n# table t\nindex,a,b,c\n" + rows + "# table small\nx\n0.250\n";
  for (const bool shared : {false, true}) {
    Stream s =
        shared ? parse_stream(std::make_shared<const std::string>(text), "in") : parse_stream(text, "in");
    REQUIRE(s.get("t", "test").rows() == 30000);
    REQUIRE(s.get("t", "test").source);
    const std::string out = format_stream(s);
    CHECK(out.find("# table t\nindex,a,b,c\n0,1.50,+2,3e0\n1,1.50,+2,3e0\n") != std::string::npos);
    CHECK(out.find("\n0.25\n") != std::string::npos);  // a small table is formatted
    CHECK(parse_stream(out, "out").get("t", "test").values == s.get("t", "test").values);
    // A value changed in place, a sign flipped to -0, a column renamed: formatted again.
    Stream changed = s;
    changed.find("t")->values[1] = 1.25;
    const std::string c1 = format_stream(changed);
    CHECK(c1.find("\n0,1.25,2,3\n1,1.5,2,3\n") != std::string::npos);
    changed = s;
    changed.find("t")->values[0] = -0.0;
    CHECK(format_stream(changed).find("\n-0,1.5,2,3\n") != std::string::npos);
    changed = s;
    changed.find("t")->columns[1] = "a2";
    CHECK(format_stream(changed).find("index,a2,b,c\n0,1.5,2,3\n") != std::string::npos);
    // A table appended to: formatted whole.
    changed = s;
    changed.find("t")->add_row({30000, 1, 2, 3});
    CHECK(format_stream(changed).find("\n29999,1.5,2,3\n30000,1,2,3\n") != std::string::npos);
  }
  // The file written by write_stream is the text format_stream gives.
  const Stream s = parse_stream(text, "in");
  const std::string path = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                           "/libsection_passthrough_test.csv";
  write_stream(path, s);
  CHECK(read_file(path) == format_stream(s));
  std::remove(path.c_str());
}

namespace {

// A stream of three sections, whole and split into parts (as the slice tool writes it).
struct ThreeSections {
  std::string whole, parted;
};

ThreeSections three_sections() {
  Stream head;
  head.units = "mm";
  head.history = {"slice --count 3 blade.ply"};
  ThreeSections t;
  Stream all = head;
  Table pts{"points", {"section", "loop", "index", "u", "v"}};
  Table frames{"frames", {"section", "z"}};
  std::vector<Stream> parts;
  for (int s = 0; s < 3; ++s) {
    Stream part;
    Table p{"points", {"section", "loop", "index", "u", "v"}};
    Table f{"frames", {"section", "z"}};
    f.add_row({double(s), 10.0 * s});
    frames.add_row({double(s), 10.0 * s});
    if (s == 1) {
      part.issues.push_back({1, -1, "slice", "no points in the slab"});
      all.issues.push_back({1, -1, "slice", "no points in the slab"});
    } else {
      for (int i = 0; i < 4; ++i) {
        p.add_row({double(s), 0, double(i), std::cos(i * 1.5) + s, std::sin(i * 1.5) / 3});
        pts.add_row({double(s), 0, double(i), std::cos(i * 1.5) + s, std::sin(i * 1.5) / 3});
      }
    }
    part.put(f);
    part.put(p);
    parts.push_back(part);
  }
  all.put(frames);
  all.put(pts);
  t.whole = format_stream(all);
  const std::string path = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                           "/libsection_parts_" + std::to_string(std::rand()) + ".csv";
  {
    StreamWriter w(path, head);
    for (int s = 0; s < 3; ++s) w.part(std::to_string(s), parts[s]);
    w.finish();
  }
  t.parted = read_file(path);
  std::remove(path.c_str());
  return t;
}

std::string temp_path(const std::string& name) {
  return std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/libsection_" + name + "_" +
         std::to_string(std::rand());
}

}  // namespace

TEST_CASE("pipe: a stream split into parts reads as the whole stream and must end with '# end'", "[pipe]") {
  const ThreeSections t = three_sections();
  REQUIRE(t.parted.find("# part 2\n") != std::string::npos);
  REQUIRE(t.parted.size() > 6);
  CHECK(t.parted.substr(t.parted.size() - 6) == "# end\n");
  // Merged, the parts give the whole stream's tables and issues.
  CHECK(format_stream(parse_stream(t.parted, "parted")) == t.whole);
  const auto message = [](const std::string& text) { return parse_error(text); };
  // Cut before '# end' (a tool that failed half way): refused.
  CHECK_THAT(message(t.parted.substr(0, t.parted.size() - 6)), Catch::Contains("lacks its closing '# end'"));
  std::string bad = t.parted;
  bad.replace(bad.rfind("section,loop,index,u,v"), 22, "section,loop,index,v,u");
  CHECK_THAT(message(bad), Catch::Contains("other columns than in the parts before"));
  bad = t.parted;
  bad.insert(bad.rfind("# end"), "# table frames\nsection,z\n");
  CHECK_THAT(message(bad), Catch::Contains("appears twice in a part"));
  CHECK_THAT(message(t.parted + "0,0\n"), Catch::Contains("after '# end'"));
  // One unit a stream: blade and tocad scaled every section by a '# units in' inside part 1,
  // camber dropped it.
  bad = t.parted;
  bad.insert(bad.find("# part 1\n") + 9, "# units in\n");
  CHECK_THAT(message(bad), Catch::Contains("'# units' in a part: a stream has one unit"));
  CHECK_THAT(message("# libsection-stream 1\n# units mm\n# units in\n"),
             Catch::Contains("a second '# units' line (in; line 2 said mm)"));
  CHECK_NOTHROW(parse_stream("# libsection-stream 1\n# units mm\n# units mm\n", "same"));
}

TEST_CASE("pipe: PartReader hands out the parts as they come and refuses a cut stream", "[pipe]") {
  const ThreeSections t = three_sections();
  const std::string in = temp_path("parts_in");
  write_file(in, t.parted);
  {
    PartReader reader(in);
    REQUIRE(reader.parted());
    CHECK(reader.source() == in);
    CHECK(reader.preamble().history == std::vector<std::string>{"slice --count 3 blade.ply"});
    std::vector<std::string> labels;
    Table points;
    for (StreamPart part; reader.next(part);) {
      labels.push_back(part.label);
      CHECK(part.text->rfind("# part " + part.label + "\n", 0) == 0);
      const Stream s = parse_stream_part(part, reader.source());
      if (const Table* p = s.find("points")) append_rows(points, *p);
    }
    CHECK(labels == std::vector<std::string>{"0", "1", "2"});
    CHECK(points.values == parse_stream(t.whole, "whole").get("points", "slice").values);
  }
  // Cut before '# end': the parts before come, then the error.
  write_file(in, t.parted.substr(0, t.parted.size() - 6));
  {
    PartReader reader(in);
    StreamPart part;
    CHECK(reader.next(part));
    CHECK(reader.next(part));
    CHECK_THROWS_WITH(reader.next(part), Catch::Contains("lacks its closing '# end'"));
  }
  // Words after '# end', and a line after it: refused once the last part is out.
  const std::string cut = t.parted.substr(0, t.parted.size() - 6);
  const std::string end_line = std::to_string(std::count(cut.begin(), cut.end(), '\n') + 1);
  for (const auto& [tail, what] :
       {std::pair<std::string, std::string>{"# end x\n", ":" + end_line + ": '# end' takes nothing"},
        {"# end\n1,2\n", ":" + std::to_string(std::stoi(end_line) + 1) + ": a line after '# end'"}}) {
    write_file(in, cut + tail);
    PartReader reader(in);
    StreamPart part;
    for (int k = 0; k < 3; ++k) CHECK(reader.next(part));
    CHECK_THROWS_WITH(reader.next(part), Catch::Contains(in + what));
  }
  // A stream not split into parts comes whole.
  write_file(in, t.whole);
  PartReader whole(in);
  CHECK_FALSE(whole.parted());
  CHECK(whole.whole() == t.whole);
  std::remove(in.c_str());
}

TEST_CASE("pipe: run_stage stages a stream part by part, the same whatever the threads", "[pipe]") {
  const ThreeSections t = three_sections();
  const std::string in = temp_path("stage_in"), out1 = temp_path("stage_out1"),
                    out2 = temp_path("stage_out2");
  write_file(in, t.parted);
  // A stage that adds a table of its own; the part's tables are seen alone.
  const auto stage = [](Stream& s, int) {
    Table twice{"twice", {"section", "u2"}};
    const Table& p = s.get("points", "slice");
    for (std::size_t r = 0; r < p.rows(); ++r) twice.add_row({p.at(r, 0), 2 * p.at(r, 3)});
    s.put(twice);
  };
  std::vector<int> seen;
  for (const auto& [threads, out] : {std::pair<int, std::string>{1, out1}, {2, out2}}) {
    StageRun run;
    run.input = in;
    run.output = out;
    run.history = "double";
    run.threads = threads;
    run.stage = stage;
    run.written = [&](const Stream& part) { seen.push_back(int(part.get("frames", "slice").at(0, 0))); };
    run_stage(run);
  }
  CHECK(seen == std::vector<int>{0, 1, 2, 0, 1, 2});  // in order
  const std::string a = read_file(out1);
  CHECK(a == read_file(out2));
  CHECK(a.find("# history double\n") != std::string::npos);
  CHECK(a.substr(a.size() - 6) == "# end\n");
  Stream whole = parse_stream(t.whole, "whole");
  stage(whole, 1);
  const Stream merged = parse_stream(a, "out");
  CHECK(merged.get("twice", "t").values == whole.get("twice", "t").values);
  CHECK(merged.issues.size() == 1);
  // A stage that fails on a part: the error goes out, no file is left behind.
  StageRun failing;
  failing.input = in;
  failing.output = out1 + ".fail";
  failing.threads = 2;
  failing.stage = [](Stream& s, int) {
    if (s.get("frames", "slice").at(0, 0) == 2) throw Error("stage: section 2 is bad");
  };
  CHECK_THROWS_WITH(run_stage(failing), Catch::Contains("section 2 is bad"));
  CHECK_THROWS(read_file(out1 + ".fail"));
  CHECK_THROWS(read_file(out1 + ".fail.partial"));
  // A cut input: refused, naming the file.
  write_file(in, t.parted.substr(0, t.parted.size() - 6));
  StageRun cut = failing;
  cut.stage = stage;
  CHECK_THROWS_WITH(run_stage(cut), Catch::Contains(in) && Catch::Contains("lacks its closing '# end'"));
  // A whole stream: staged and written whole.
  write_file(in, t.whole);
  StageRun whole_run = cut;
  whole_run.output = out1;
  run_stage(whole_run);
  CHECK(read_file(out1).find("# part") == std::string::npos);
  CHECK(parse_stream(read_file(out1), "out").get("twice", "t").values == whole.get("twice", "t").values);
  for (const auto& p : {in, out1, out2}) std::remove(p.c_str());
}

TEST_CASE("pipe: run_stage leaves columns a stage never reads undecoded, refusing bad cells alike",
          "[pipe]") {
  // Two parts whose points tables are large enough to be passed on as text.
  const std::string path = temp_path("unread_in"), out = temp_path("unread_out");
  const auto stream = [&](const std::string& units, const std::string& bad) {
    Stream head;
    head.units = units;
    StreamWriter w(path, head);
    for (int s = 0; s < 2; ++s) {
      Stream part;
      Table p{"points", {"section", "loop", "index", "u", "nu"}};
      for (int i = 0; i < 300; ++i) p.add_row({double(s), 0, double(i), i / 8.0 + s, std::sin(i / 3.0)});
      part.put(p);
      w.part(std::to_string(s), part);
    }
    w.finish();
    std::string text = read_file(path);
    if (!bad.empty()) {  // the last row's nu
      const std::size_t end = text.rfind("\n# end"), at = text.rfind(',', end) + 1;
      text.replace(at, end - at, bad);
    }
    write_file(path, text);
    return path;
  };
  // Runs a stage reading u alone; returns its output, the nu values it saw NaN, or the error.
  const auto run = [&](const std::string& in, bool unread, std::size_t& nan) {
    nan = 0;
    StageRun r;
    r.input = in;
    r.output = out;
    r.threads = 1;
    if (unread) r.unread = {{"points", "nu"}};
    r.stage = [&](Stream& s, int) {
      const Table& p = s.get("points", "t");
      Table sum{"sum", {"section", "u"}, {p.at(0, 0), 0}};
      for (std::size_t k = 0; k < p.rows(); ++k) sum.values[1] += p.at(k, 3), nan += std::isnan(p.at(k, 4));
      s.put(sum);
    };
    const std::string error = thrown([&] { run_stage(r); });
    return error == "no error" ? read_file(out) : error;
  };
  std::size_t nan = 0, none = 0;
  const std::string mm = stream("mm", "");
  const std::string passed = run(mm, true, nan);
  CHECK(nan == 600);                      // undecoded ...
  CHECK(passed == run(mm, false, none));  // ... and passed on as they came
  CHECK(none == 0);
  // In another unit every value is converted, and written from its values: all decoded.
  CHECK(run(stream("in", ""), true, nan) == run(stream("in", ""), false, none));
  CHECK(nan == 0);
  // A bad cell is refused as ever, naming its line (the last).
  for (const std::string bad : {"x", "1e16", "nan", "-", "1e-400x", "1,2"}) {
    const std::string in = stream("mm", bad), refused = run(in, false, none);
    CHECK_THAT(refused, Catch::Contains(":608: ") && Catch::Contains("table 'points'"));
    CHECK(run(in, true, nan) == refused);
  }
  // Cells of other forms a number may take are read as ever.
  for (const std::string odd : {"1e-5", "+0.5", "0.12345678901234567890123", " 1", "1234567890123456e-3"}) {
    const std::string in = stream("mm", odd), kept = run(in, false, none);
    CHECK(kept.find(odd) != std::string::npos);
    CHECK(run(in, true, nan) == kept);
  }
  for (const auto& p : {out, path}) std::remove(p.c_str());
}

TEST_CASE("pipe: writing refuses NaN rather than passing it on", "[pipe]") {
  Stream s;
  Table t{"t", {"a"}, {}};
  t.add_row({std::numeric_limits<double>::quiet_NaN()});
  s.put(t);
  REQUIRE_THROWS_AS(format_stream(s), Error);
}

TEST_CASE("pipe: plain CSV tables and 2D profiles", "[pipe]") {
  const Table t = parse_csv("# planes\norigin_x,origin_y\n1,2\n3 4\n", "planes.csv");
  REQUIRE(t.rows() == 2);
  CHECK(t.at(1, t.column("origin_y")) == 4);
  REQUIRE_THROWS_WITH(parse_csv("a,b\n1\n", "p.csv"), Catch::Contains("p.csv:2"));
  const auto prof = parse_profile("NACA 0012\n1.0 0.0\n0.5,0.06 extra\n0 0\n", "naca.dat");
  REQUIRE(prof.size() == 3);
  CHECK(prof[1].y() == 0.06);
  REQUIRE_THROWS_WITH(parse_profile("1 0\n0.5 x\n", "p.dat"), Catch::Contains("p.dat:2"));
  // A header names the columns: x and y wherever they stand; three or more names without
  // them leave the profile's columns unknown (the first two were a point number and x).
  const auto named = parse_profile("id,y,x\n1,2,3\n2,4,5\n", "named.csv");
  REQUIRE(named.size() == 2);
  CHECK(named[1] == Eigen::Vector2d(5, 4));
  REQUIRE_THROWS_WITH(
      parse_profile("point,x_mm,y_mm\n1,0,0\n2,1,0.1\n", "cmm.csv"),
      Catch::Contains("cmm.csv:1: the header names the columns point, x_mm, y_mm but none x and y"));
  // A title of three words over two columns is a title.
  CHECK(parse_profile("LS89 vane profile\n0 0\n1 0.1\n", "t.dat").size() == 2);
  // Exact copies count once, in the order first read: every line twice, a closing point, -0.
  const auto twice = parse_profile("0 0\n0 0\n1 0\n1 0\n1 1\n1 1\n-0 0\n", "twice.dat");
  REQUIRE(twice.size() == 3);
  CHECK(twice[2] == Eigen::Vector2d(1, 1));
}

TEST_CASE("frame: a +z normal gives u = x, v = y, the frame is orthonormal and its u keeps to tilts",
          "[pipe]") {
  const Frame f = make_frame({0, 0, 5}, {0, 0, 3});
  CHECK((f.u - Eigen::Vector3d::UnitX()).norm() < 1e-15);
  CHECK((f.v - Eigen::Vector3d::UnitY()).norm() < 1e-15);
  const Frame g = make_frame({1, 2, 3}, {0.3, -0.5, 0.8});
  CHECK(std::abs(g.u.dot(g.v)) < 1e-15);
  CHECK((g.u.cross(g.v) - g.n).norm() < 1e-15);
  const Eigen::Vector3d p(4, -1, 2);
  const Eigen::Vector3d back = g.to_world(g.to_plane(p)) + g.height(p) * g.n;
  CHECK((back - p).norm() < 1e-12);
  REQUIRE_THROWS_AS(make_frame({0, 0, 0}, {0, 0, 0}), Error);
  // Normals tilted a little off a world axis, either way, keep that axis's u (rows fitted one
  // by one: u swapped between x and y as the tilt's direction changed): u within the tilt of
  // the axis's u, and the world axes give what they gave.
  const double t = 0.05;
  for (const Eigen::Vector3d& tilt : {Eigen::Vector3d(t, 0, 0), Eigen::Vector3d(0, t, 0),
                                      Eigen::Vector3d(t, -t / 2, 0), Eigen::Vector3d(-t / 3, t, 0)}) {
    CHECK(make_frame({0, 0, 0}, Eigen::Vector3d(0, 0, 1) + tilt).u.dot(Eigen::Vector3d::UnitX()) > 1 - t * t);
    CHECK(make_frame({0, 0, 0}, Eigen::Vector3d(1, tilt.x(), tilt.y())).u.dot(Eigen::Vector3d::UnitY()) >
          1 - t * t);
    CHECK(make_frame({0, 0, 0}, Eigen::Vector3d(tilt.x(), 1, tilt.y())).u.dot(Eigen::Vector3d::UnitX()) >
          1 - t * t);
  }
  CHECK(make_frame({0, 0, 0}, {1, 0, 0}).u == Eigen::Vector3d::UnitY());
  CHECK(make_frame({0, 0, 0}, {0, 1, 0}).u == Eigen::Vector3d::UnitX());
  CHECK(make_frame({0, 0, 0}, {0, 0, -1}).u == Eigen::Vector3d::UnitX());
}
