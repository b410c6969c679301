// SPDX-License-Identifier: GPL-3.0-or-later
// The stream's own number reader (io/plain_number.h) gives the double std::from_chars gives,
// bit for bit, or leaves the text to it.
#include "io/plain_number.h"
#include "io/shortest_number.h"
#include "io/stream_text.h"
#include "section/io/stream.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

// `s` alone, followed by more of a row (where plain_number reads 16 bytes at once) and after
// a row's first cells (where it may read the 16 bytes that end at a fraction's last digit).
struct Place {
  std::string before, after;
};
const std::vector<Place> places = {{"", ""},
                                   {"", ",12345678901234567890\n"},
                                   {"", "\n"},
                                   {"0,1,2345,-0.9876543210987654,", ",0\n"},
                                   {"99999999999999999999999999999999,", ""},
                                   {"3,4,5,6,7,8,9,10,", "\n7,8,9,10,11,12,13,14,15,16,17,18\n"}};

// True when plain_number reads all of `s` as from_chars does, or declines it, in each place.
bool agrees(const std::string& s) {
  double theirs = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), theirs);
  for (const Place& place : places) {
    const std::string text = place.before + s + place.after;
    const char* const at = text.data() + place.before.size();
    double mine = 0;
    const char* const end = section::detail::plain_number(text.data(), at, text.data() + text.size(), mine);
    if (!end || end != at + s.size()) continue;  // declined, or read a part: the caller falls back
    if (r.ptr != s.data() + s.size() || std::memcmp(&mine, &theirs, sizeof mine) != 0) return false;
  }
  return true;
}

// In how many of its places plain_number reads all of `s`.
int reads(const std::string& s) {
  int n = 0;
  for (const Place& place : places) {
    const std::string text = place.before + s + place.after;
    const char* const at = text.data() + place.before.size();
    double v = 0;
    n += section::detail::plain_number(text.data(), at, text.data() + text.size(), v) == at + s.size();
  }
  return n;
}

}  // namespace

TEST_CASE("stream numbers: plain_number reads what the writers write, as from_chars does", "[pipe]") {
  for (const char* s : {"0", "-0", "-0.0", "5208", "0.05567185234345313", "19.619593363634294",
                        "-0.9794720536585177", "9007199254740992", "9999999999999999999",
                        "1.0000000000000002", "123456789.12345678", "0.000000000000000001",
                        // fractions ending in each of the first and second eight bytes, or after them
                        "7.1234567", "7.12345678", "7.123456789", "-12.123456789012345", "0.1234567890123456",
                        "0.12345678901234567", "-12.1234567890123456", "123.1234567890123456"}) {
    CAPTURE(s);
    CHECK(reads(s) == int(places.size()));
    CHECK(agrees(s));
  }
  double v = 1;
  section::detail::plain_number("-0", "-0", "-0" + 2, v);
  CHECK(std::signbit(v));
  // Other forms are left to from_chars: a sign, an exponent, 20 digits, no digit before or
  // after the point; and an exact midpoint between two doubles (2^53 + 1).
  for (const char* s : {"+1", "1e5", "12345678901234567890", "0.0000000000000000001", ".5", "5.", "-", "",
                        " 1", "inf", "nan", "9007199254740993"}) {
    CAPTURE(s);
    CHECK(reads(s) == 0);
  }
  // Doubles in their shortest and fixed forms, and 17 to 19 digits near the midpoints
  // between two doubles, where rounding twice could go wrong.
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> unit(1, 10);
  char buf[64];
  long checked = 0;
  for (int k = 0; k < 300000; ++k) {
    const double d = (k % 2 ? -1 : 1) * unit(rng) * std::pow(10.0, int(rng() % 24) - 12);
    const auto r = std::to_chars(buf, buf + sizeof buf, d);
    checked += reads(std::string(buf, r.ptr)) == int(places.size());
    REQUIRE(agrees(std::string(buf, r.ptr)));
    const double up = std::nextafter(d, 2 * d);
    const long double mid = (static_cast<long double>(d) + up) / 2;
    std::snprintf(buf, sizeof buf, "%.*Lf", int(17 + rng() % 3 - std::floor(std::log10(std::abs(d))) - 1),
                  mid);
    REQUIRE(agrees(buf));
  }
  CHECK(checked > 150000);
}

TEST_CASE("stream numbers: random decimals in every form read as from_chars reads them", "[pipe]") {
  std::mt19937_64 rng(2025);
  const auto digits = [&](int n) {
    std::string d;
    for (int k = 0; k < n; ++k) d += char('0' + rng() % 10);
    return d;
  };
  char buf[512];
  long read = 0;
  for (int k = 0; k < 200000; ++k) {
    // Random digit strings: 1 to 4 digits (leading zeros too) before the point, 1 to 21 after.
    const std::string sign = rng() % 3 ? "" : rng() % 2 ? "-" : "+";
    const std::string fixed = sign + digits(1 + int(rng() % 4)) + "." + digits(1 + int(rng() % 21));
    read += reads(fixed) > 0;
    REQUIRE(agrees(fixed));
    // Random doubles over the whole range, denormals included, in fixed form with 0 to 25
    // decimals, shortest and scientific (the latter left to from_chars).
    std::uint64_t bits = rng() & ~(std::uint64_t(0x7FF) << 52);
    bits |= std::uint64_t(rng() % 2 ? 1023 - 70 + rng() % 120 : rng() % 2047) << 52;
    double d;
    std::memcpy(&d, &bits, sizeof d);
    std::snprintf(buf, sizeof buf, "%.*f", int(rng() % 26), d);
    REQUIRE(agrees(buf));
    std::snprintf(buf, sizeof buf, "%.*e", int(rng() % 20), d);
    REQUIRE(agrees(buf));
    REQUIRE(reads(buf) == 0);
    const auto r = std::to_chars(buf, buf + sizeof buf, d);
    REQUIRE(agrees(std::string(buf, r.ptr)));
    // Halfway between two doubles, exactly (up to 19 digits: 2^53 + 1 and its like) and in
    // 16 to 19 digits.
    const std::uint64_t odd = (std::uint64_t(1) << 53) + 1 + 2 * (rng() % 100000);
    REQUIRE(agrees(std::to_string(odd)));
    const long double up = std::nextafter(std::abs(d), 1e300);
    const long double mid = (static_cast<long double>(std::abs(d)) + up) / 2;
    if (std::abs(d) > 1e-3 && std::abs(d) < 1e15) {
      std::snprintf(buf, sizeof buf, "%.*Lf", int(16 + rng() % 4 - std::floor(std::log10(std::abs(d))) - 1),
                    mid);
      REQUIRE(agrees(buf));
    }
  }
  CHECK(read > 60000);  // (the others: a '+', over 19 digits, or a midpoint left to from_chars)
}

TEST_CASE("stream numbers: rows with repeated and changing ids read cell for cell as from_chars does",
          "[pipe]") {
  // Sections and loops that stay for some rows and change, in 1 to 3 digits, one the start of
  // another's text (the leading ids are taken again from the row before only where their
  // text is the same).
  std::mt19937_64 rng(77);
  const int ids[] = {0, 1, 10, 12, 100, 120, 2, 21};
  std::string rows;
  std::vector<std::vector<std::string>> cells;
  int section = 0, loop = 0;
  for (int i = 0; i < 5000; ++i) {
    if (rng() % 9 == 0) section = ids[rng() % 8];
    if (rng() % 4 == 0) loop = ids[rng() % 8];
    std::vector<std::string> row = {std::to_string(section), std::to_string(loop), std::to_string(i)};
    for (int c = 0; c < 2; ++c) {
      const double v = (rng() % 2 ? -1 : 1) * std::ldexp(double(rng() >> 11), -10 - int(rng() % 60));
      char buf[64];
      const auto r = std::to_chars(buf, buf + sizeof buf, v);
      row.emplace_back(buf, r.ptr);
    }
    rows += row[0] + "," + row[1] + "," + row[2] + "," + row[3] + "," + row[4] + "\n";
    cells.push_back(row);
  }
  const section::Stream s =
      section::parse_stream("# libsection-stream 1\n# table t\nsection,loop,index,a,b\n" + rows, "s.csv");
  const section::Table& t = s.get("t", "test");
  REQUIRE(t.rows() == cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (std::size_t c = 0; c < 5; ++c) {
      double theirs = 0;
      std::from_chars(cells[i][c].data(), cells[i][c].data() + cells[i][c].size(), theirs);
      const double mine = t.at(i, c);
      CAPTURE(i, c, cells[i][c]);
      REQUIRE(std::memcmp(&mine, &theirs, sizeof mine) == 0);
    }
}

TEST_CASE("stream numbers: shortest_number writes what std::to_chars writes, or declines", "[pipe]") {
  const auto agrees_to_chars = [](double v) {
    char mine[64], theirs[64];
    const char* end = section::detail::shortest_number(mine, v);
    if (!end) return true;  // declined: the writer uses to_chars
    const auto r = std::to_chars(theirs, theirs + sizeof theirs, v);
    return std::string(mine, std::size_t(end - mine)) == std::string(theirs, std::size_t(r.ptr - theirs));
  };
  const auto writes = [](double v, const char* text) {
    char buf[64];
    const char* end = section::detail::shortest_number(buf, v);
    return end && std::string(buf, std::size_t(end - buf)) == text;
  };
  // Fixed and scientific forms, whichever is shorter (fixed on a tie).
  CHECK(writes(19.619593363634294, "19.619593363634294"));
  CHECK(writes(-0.9794720536585177, "-0.9794720536585177"));
  CHECK(writes(0.1, "0.1"));
  CHECK(writes(0.001, "0.001"));
  CHECK(writes(0.0001, "1e-04"));
  CHECK(writes(0.00012, "0.00012"));
  CHECK(writes(1.5e-05, "1.5e-05"));
  CHECK(writes(123456789012345.6, "123456789012345.6"));
  CHECK(writes(3e14, "3e+14"));
  CHECK(writes(300000.0, "3e+05"));
  CHECK(writes(1.0 / 3, "0.3333333333333333"));
  // Outside its range, and powers of two: left to to_chars.
  for (const double v : {0.0, 1.0, 0.5, 1e-6, 1e15, 1e300, -4.0})
    CHECK(section::detail::shortest_number(nullptr, v) == nullptr);
  // Random doubles of every significand across the range, short decimals and their
  // neighbours (where the interval's ends decide).
  std::mt19937_64 rng(31);
  long written = 0;
  for (int k = 0; k < 400000; ++k) {
    std::uint64_t bits = (rng() & ((std::uint64_t(1) << 52) - 1)) | (std::uint64_t(1005 + rng() % 68) << 52) |
                         (std::uint64_t(k % 2) << 63);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    char buf[64];
    written += section::detail::shortest_number(buf, v) != nullptr;
    REQUIRE(agrees_to_chars(v));
    const int digits = 1 + int(rng() % 17);
    const double d =
        double(rng() % std::uint64_t(std::pow(10.0, digits))) * std::pow(10.0, int(rng() % 20) - 6 - digits);
    REQUIRE(agrees_to_chars(d));
    REQUIRE(agrees_to_chars(std::nextafter(d, 1e300)));
    REQUIRE(agrees_to_chars(std::nextafter(d, 0.0)));
  }
  CHECK(written > 380000);  // (2 of its 68 exponents are outside the range)
}

TEST_CASE("stream numbers: rows in other forms and bad rows among plain ones", "[pipe]") {
  std::string rows;
  for (int i = 0; i < 2000; ++i)
    rows += std::to_string(i) + (i % 97 == 5   ? ", 1.5e0 ,+2\r\n"
                                 : i % 89 == 3 ? ",0.25,-3.\n\n"
                                               : ",0.25,-3.5\n");
  const std::string head = "# libsection-stream 1\n# units mm\n# table t\nindex,a,b\n";
  const section::Stream s = section::parse_stream(head + rows, "s.csv");
  const section::Table& t = s.get("t", "test");
  REQUIRE(t.rows() == 2000);
  CHECK(t.at(5, 1) == 1.5);
  CHECK(t.at(5, 2) == 2);
  CHECK(t.at(3, 2) == -3);
  CHECK(t.at(4, 2) == -3.5);
  // A bad cell: the line-by-line parse names its line.
  std::string bad = rows;
  bad.replace(bad.find("\n1500,") + 1, 4, "15x0");
  const std::string text = head + bad;
  const auto line = std::count(text.begin(), text.begin() + long(text.find("15x0")), '\n') + 1;
  try {
    section::parse_stream(text, "s.csv");
    FAIL("no error");
  } catch (const std::exception& e) {
    CHECK_THAT(e.what(), Catch::Contains("s.csv:" + std::to_string(line) + ":") && Catch::Contains("'15x0'"));
  }
}

TEST_CASE("stream text: count_lines counts every line end, at any offset and length", "[pipe]") {
  std::string text;
  std::mt19937_64 rng(7);
  while (text.size() < 20000) text += std::string(rng() % 90, 'x') + (rng() % 5 ? "\n" : "\n\n");
  text += std::string(300 * 64, '\n');  // more than 255 in one byte lane
  for (std::size_t from : {0, 1, 15, 63, 64, 100})
    for (std::size_t size : {0, 1, 16, 63, 64, 65, 127, 4095, 4097, 16000, 38000}) {
      CAPTURE(from, size);
      const std::string_view s = std::string_view(text).substr(from, size);
      CHECK(section::detail::count_lines(s) == std::size_t(std::count(s.begin(), s.end(), '\n')));
    }
}
