#include "section/io/stream.h"

#include "section/io/csv.h"
#include "section/io/file.h"
#include "section/pipe/run_stage.h"

#include "section/error.h"
#include "detail/parallel.h"
#include "io/text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <fstream>
#include <iostream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>

namespace section {

std::size_t Table::column(const std::string& column_name) const {
  const long c = find_column(column_name);
  if (c < 0) throw Error("pipe: table '" + name + "' has no column '" + column_name + "'");
  return static_cast<std::size_t>(c);
}

long Table::find_column(const std::string& column_name) const {
  const auto it = std::find(columns.begin(), columns.end(), column_name);
  return it == columns.end() ? -1 : static_cast<long>(it - columns.begin());
}

void Table::add_row(std::initializer_list<double> row) {
  if (row.size() != columns.size())
    throw Error("pipe: a row of table '" + name + "' has " + std::to_string(row.size()) +
                " values for " + std::to_string(columns.size()) + " columns");
  values.insert(values.end(), row.begin(), row.end());
}

void Table::add_row(const std::vector<double>& row) {
  if (row.size() != columns.size())
    throw Error("pipe: a row of table '" + name + "' has " + std::to_string(row.size()) +
                " values for " + std::to_string(columns.size()) + " columns");
  values.insert(values.end(), row.begin(), row.end());
}

const Table* Stream::find(const std::string& name) const {
  for (const auto& t : tables)
    if (t.name == name) return &t;
  return nullptr;
}

Table* Stream::find(const std::string& name) {
  for (auto& t : tables)
    if (t.name == name) return &t;
  return nullptr;
}

const Table& Stream::get(const std::string& name, const std::string& produced_by) const {
  if (const Table* t = find(name)) return *t;
  throw Error("pipe: the stream has no '" + name + "' table (it is written by " + produced_by +
              ")");
}

void Stream::put(Table table) {
  if (Table* t = find(table.name))
    *t = std::move(table);
  else
    tables.push_back(std::move(table));
}

void Stream::erase(const std::string& name) {
  tables.erase(std::remove_if(tables.begin(), tables.end(),
                              [&](const Table& t) { return t.name == name; }),
               tables.end());
}

bool Stream::failed(int section, int loop) const {
  return std::any_of(issues.begin(), issues.end(), [&](const SectionIssue& i) {
    return i.section == section && (i.loop == -1 || loop == -1 || i.loop == loop);
  });
}

namespace {

using detail::parse_double;
using detail::trim;

[[noreturn]] void fail(const std::string& source, std::size_t line, const std::string& what) {
  throw Error("pipe: " + source + ":" + std::to_string(line) + ": " + what);
}

std::vector<std::string> split_header(std::string_view line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.emplace_back(trim(line.substr(start, comma == std::string_view::npos ? line.npos
                                                                              : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// `# issue section=S loop=L stage=NAME message=TEXT`
SectionIssue parse_issue(std::string_view rest, const std::string& source, std::size_t line) {
  SectionIssue issue;
  const auto take = [&](std::string_view key) -> std::string_view {
    const std::string needle = std::string(key) + "=";
    const std::size_t at = rest.find(needle);
    if (at == std::string_view::npos) fail(source, line, "issue line without '" + needle + "'");
    std::string_view value = rest.substr(at + needle.size());
    if (key != "message") value = value.substr(0, value.find(' '));
    return value;
  };
  const auto to_int = [&](std::string_view s) {
    int v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
      fail(source, line, "issue line with a bad id '" + std::string(s) + "'");
    return v;
  };
  issue.section = to_int(take("section"));
  issue.loop = to_int(take("loop"));
  issue.stage = std::string(take("stage"));
  issue.message = std::string(take("message"));
  return issue;
}

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
}

}  // namespace

namespace {

// A cell of 1 to 9 digits, optionally after '-' (ids, indices, counts): its value without
// from_chars, the same double (such integers are exact).
inline bool small_integer(std::string_view cell, double& value) {
  const bool minus = !cell.empty() && cell.front() == '-';
  if (minus) cell.remove_prefix(1);
  if (cell.empty() || cell.size() > 9) return false;
  int v = 0;
  for (const char ch : cell) {
    if (ch < '0' || ch > '9') return false;
    v = 10 * v + (ch - '0');
  }
  value = minus ? -double(v) : double(v);
  return true;
}

// One data row of `columns` cells appended to `out`; false on anything parse_stream's
// checks refuse (the serial parse then finds and names the problem).
bool parse_row(std::string_view line, const std::vector<char>& id_column, std::vector<double>& out) {
  const std::size_t columns = id_column.size();
  std::size_t start = 0, col = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view cell = trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start));
    if (col == columns) return false;
    double value = 0;
    if (!small_integer(cell, value) &&
        (!parse_double(cell, value) || !std::isfinite(value) || std::abs(value) > detail::max_coordinate))
      return false;
    if (id_column[col] && (value != std::floor(value) || std::abs(value) > 2147483647.0)) return false;
    out.push_back(value);
    ++col;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return col == columns;
}

// The data rows of text[0, size) (whole lines, blank ones skipped) into `out`; false when
// any row is refused.
bool parse_rows(std::string_view text, const std::vector<char>& id_column, std::vector<double>& out) {
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (trim(line).empty()) continue;
    if (!parse_row(line, id_column, out)) return false;
  }
  return true;
}

// A `# key rest` line: its key ("table", "part", "history", ...) and the rest, trimmed
// (line ends dropped).
struct MetaLine {
  std::string_view key, rest, body;  // body: all after '#', trimmed
};

MetaLine meta_line(std::string_view line) {
  std::string_view body = trim(line.substr(1));
  while (!body.empty() && (body.back() == '\n' || body.back() == '\r')) body.remove_suffix(1);
  const std::size_t space = body.find(' ');
  return {body.substr(0, space), space == std::string_view::npos ? std::string_view{} : trim(body.substr(space)),
          body};
}

// The error for a stream split into parts that lacks its `# end`.
Error truncated_parts(const std::string& source) {
  return Error("pipe: " + source + ": the stream is split into parts but lacks its closing '# end' line (truncated "
               "stream, or the tool that wrote it failed)");
}

// A part of a stream split into parts (run_stage) is parsed alone: no version line, its
// lines numbered from `first_line`.
struct PartText {
  bool is_part = false;
  std::size_t first_line = 1;
};

// parse_stream; the source rows of large tables are kept as parts of `owner` when it
// holds `text`, else as copies.
Stream parse_stream_text(std::string_view text, const std::string& source,
                         const std::shared_ptr<const std::string>& owner, const PartText& part = {}) {
  Stream stream;
  if (const char* why = detail::text_encoding_problem(text)) throw Error("pipe: " + source + ": " + why);
  if (!part.is_part) detail::skip_bom(text);
  if (text.empty()) throw Error("pipe: " + source + ": the stream is empty");
  Table* current = nullptr;
  bool expect_header = false;
  bool seen_version = part.is_part;
  std::size_t line_no = part.first_line - 1;
  // Parts (docs/FORMAT.md): a table may come again in a later part, with the same header.
  std::size_t parts = 0;
  bool ended = false;
  std::vector<std::string> in_part;       // tables seen in the current part
  std::vector<std::string> continued_columns;  // header a continued table must repeat (empty: a new table)
  std::size_t pos = 0;
  std::vector<double> row;
  std::vector<char> id_column;  // per column of the current table: holds integer ids
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (trim(line).empty()) continue;
    if (line[0] == '#') {
      const auto [key, rest, body] = meta_line(line);
      if (expect_header) fail(source, line_no, "table '" + current->name + "' has no header row");
      if (ended) fail(source, line_no, "a line after '# end'");
      if (!seen_version) {
        if (key != "libsection-stream")
          fail(source, line_no,
               "not a libsection stream (the first line must be '# libsection-stream 1')");
        if (rest != std::to_string(stream_version))
          fail(source, line_no, "stream version '" + std::string(rest) + "' is not supported (this "
                                "build reads version " + std::to_string(stream_version) + ")");
        seen_version = true;
        continue;
      }
      current = nullptr;
      if (key == "table") {
        if (rest.empty()) fail(source, line_no, "'# table' without a name");
        const std::string name(rest);
        if (std::find(in_part.begin(), in_part.end(), name) != in_part.end() || (parts == 0 && stream.find(name)))
          fail(source, line_no, "table '" + name + "' appears twice" + (parts ? " in a part" : ""));
        in_part.push_back(name);
        continued_columns.clear();
        if (Table* earlier = stream.find(name)) {
          // The same table in a later part: its rows follow those before.
          continued_columns = earlier->columns;
          earlier->source = nullptr;  // its text is no longer one piece
          current = earlier;
        } else {
          stream.tables.push_back(Table{name, {}, {}});
          current = &stream.tables.back();
        }
        expect_header = true;
      } else if (key == "part") {
        if (part.is_part && parts > 0) fail(source, line_no, "two parts in one");
        ++parts;
        in_part.clear();
      } else if (key == "end") {
        if (!rest.empty()) fail(source, line_no, "'# end' takes nothing after it");
        ended = true;
      } else if (key == "units") {
        if (rest.empty()) fail(source, line_no, "'# units' without a unit");
        stream.units = std::string(rest);
      } else if (key == "history") {
        stream.history.emplace_back(rest);
      } else if (key == "issue") {
        stream.issues.push_back(parse_issue(rest, source, line_no));
      } else {
        stream.notes.emplace_back(body);
      }
      continue;
    }
    if (!seen_version)
      fail(source, line_no, "not a libsection stream (the first line must be '# libsection-stream 1')");
    if (ended) fail(source, line_no, "a line after '# end'");
    if (!current) fail(source, line_no, "a data row outside any table (missing '# table NAME')");
    if (expect_header) {
      const std::vector<std::string> header = split_header(line);
      if (!continued_columns.empty() && header != continued_columns)
        fail(source, line_no, "table '" + current->name + "' has other columns than in the parts before");
      current->columns = header;
      for (const auto& c : current->columns)
        if (c.empty()) fail(source, line_no, "empty column name in the header of table '" + current->name + "'");
      id_column.assign(current->columns.size(), 0);
      for (std::size_t c = 0; c < current->columns.size(); ++c) {
        const std::string& n = current->columns[c];
        id_column[c] = n == "section" || n == "loop" || n == "index";
      }
      expect_header = false;
      // The table's data rows run to the next line starting with '#': large blocks are
      // parsed in pieces by all cores, appended in order. A piece that refuses a row sends
      // the block through the line-by-line parse below, whose error names the line.
      const std::size_t block_start = std::min(pos, text.size());  // pos is past the end after a last line without '\n'
      std::size_t block_end = block_start;
      while (block_end < text.size() && text[block_end] != '#') {
        const std::size_t nl = text.find('\n', block_end);
        block_end = nl == std::string_view::npos ? text.size() : nl + 1;
      }
      const std::string_view block = text.substr(block_start, block_end - block_start);
      // Blocks of a few kB and up: a section's table in a stream split into parts.
      if (block.size() >= (std::size_t(1) << 12)) {
        const std::size_t parts = std::max<std::size_t>(1, std::min<std::size_t>(64, block.size() >> 17));
        std::vector<std::size_t> cut(parts + 1, 0);
        cut[parts] = block.size();
        for (std::size_t k = 1; k < parts; ++k) {
          const std::size_t at = block.find('\n', std::max(cut[k - 1], block.size() * k / parts));
          cut[k] = at == std::string_view::npos ? block.size() : at + 1;
        }
        std::vector<std::vector<double>> piece(parts);
        std::vector<char> ok(parts, 0);
        detail::parallel_for(parts, 0, [&](std::size_t k) {
          piece[k].reserve((cut[k + 1] - cut[k]) / 8);
          ok[k] = parse_rows(block.substr(cut[k], cut[k + 1] - cut[k]), id_column, piece[k]);
        });
        if (std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; })) {
          std::size_t total = 0;
          for (const auto& v : piece) total += v.size();
          current->values.reserve(current->values.size() + total);
          for (const auto& v : piece) current->values.insert(current->values.end(), v.begin(), v.end());
          // Kept to be written back as it is (Table::source); not with '\r' line ends,
          // which the written stream does not use.
          if (continued_columns.empty() && block.find('\r') == std::string_view::npos) {
            auto kept = std::make_shared<TableText>();
            if (owner) {
              kept->text = owner;
              kept->rows = block;
            } else {
              kept->text = std::make_shared<const std::string>(block);
              kept->rows = *kept->text;
            }
            kept->columns = current->columns;
            kept->values = current->values;
            current->source = std::move(kept);
          }
          line_no += std::count(block.begin(), block.end(), '\n');
          if (!block.empty() && block.back() != '\n') ++line_no;  // the last line has no newline
          pos = block_end;
        }
      }
      continue;
    }
    row.clear();
    std::size_t start = 0;
    std::size_t col = 0;
    while (true) {
      const std::size_t comma = line.find(',', start);
      const std::string_view cell =
          trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start));
      ++col;
      if (col > current->columns.size())
        fail(source, line_no, "more values than the " + std::to_string(current->columns.size()) +
                                  " columns of table '" + current->name + "'");
      double value = 0;
      if (!parse_double(cell, value))
        fail(source, line_no, "column '" + current->columns[col - 1] + "' of table '" +
                                  current->name + "': expected a number, found '" +
                                  std::string(cell.substr(0, 40)) + "'");
      if (!std::isfinite(value))
        fail(source, line_no, "column '" + current->columns[col - 1] + "' of table '" +
                                  current->name + "': non-finite value '" + std::string(cell.substr(0, 40)) + "'");
      if (std::abs(value) > detail::max_coordinate)
        fail(source, line_no, "column '" + current->columns[col - 1] + "' of table '" + current->name +
                                  "': value " + std::string(cell.substr(0, 40)) + " is beyond +-1e15 (corrupt stream?)");
      // Ids become ints in every stage: a fraction or a value beyond int would be cast silently.
      if (id_column[col - 1] && (value != std::floor(value) || std::abs(value) > 2147483647.0))
        fail(source, line_no, "column '" + current->columns[col - 1] + "' of table '" + current->name +
                                  "': '" + std::string(cell.substr(0, 40)) + "' is not an integer id");
      row.push_back(value);
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (row.size() != current->columns.size())
      fail(source, line_no, std::to_string(row.size()) + " values for the " +
                                std::to_string(current->columns.size()) + " columns of table '" +
                                current->name + "' (truncated line?)");
    current->values.insert(current->values.end(), row.begin(), row.end());
  }
  if (!seen_version) throw Error("pipe: " + source + ": the stream is empty");
  if (expect_header)
    throw Error("pipe: " + source + ": table '" + current->name + "' has no header row (truncated stream?)");
  if (parts > 0 && !ended && !part.is_part) throw truncated_parts(source);
  return stream;
}

}  // namespace

Stream parse_stream(std::string_view text, const std::string& source) {
  return parse_stream_text(text, source, nullptr);
}

Stream parse_stream(std::shared_ptr<const std::string> text, const std::string& source) {
  if (!text) throw Error("pipe: " + source + ": no text");
  return parse_stream_text(*text, source, text);
}

std::string format_number(double value) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, r.ptr);
}

namespace {

// Writes v as std::to_chars(double) does (shortest round trip, fixed or scientific,
// whichever is shorter, fixed on a tie). Integers below 100000 in magnitude (ids, counts)
// print in fixed notation, digit by digit, much faster.
inline char* put_number(char* p, double v) {
  if (v > -100000 && v < 100000) {
    const int k = int(v);
    if (double(k) == v && !(k == 0 && std::signbit(v))) {
      unsigned u = k < 0 ? unsigned(-k) : unsigned(k);
      if (k < 0) *p++ = '-';
      char digits[8];
      int n = 0;
      do {
        digits[n++] = char('0' + u % 10);
        u /= 10;
      } while (u);
      while (n) *p++ = digits[--n];
      return p;
    }
  }
  return std::to_chars(p, p + 32, v).ptr;
}

// Rows [r0, r1) of a table's values as text.
std::string format_rows(const Table& t, std::size_t r0, std::size_t r1) {
  const std::size_t cols = t.columns.size();
  std::string out((r1 - r0) * cols * 25, '\0');  // a double takes at most 24 characters
  char* p = out.data();
  const double* v = t.values.data() + r0 * cols;
  for (std::size_t r = r0; r < r1; ++r) {
    for (std::size_t c = 0; c < cols; ++c) {
      p = put_number(p, *v++);
      *p++ = ',';
    }
    p[-1] = '\n';
  }
  out.resize(std::size_t(p - out.data()));
  return out;
}

// True when `t` holds what its source text reads as (bit for bit: -0 is not 0).
bool unchanged_since_read(const Table& t) {
  const TableText* src = t.source.get();
  return src && src->columns == t.columns && src->values.size() == t.values.size() &&
         (t.values.empty() || std::memcmp(src->values.data(), t.values.data(), t.values.size() * sizeof(double)) == 0);
}


// The stream's text in order: formatted pieces and the source rows of unchanged tables.
struct FormattedStream {
  std::vector<std::string> formatted;  // pieces made here
  std::vector<std::string_view> parts; // every piece in order: views of `formatted` or of sources
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& p : parts) n += p.size();
    return n;
  }
};

// The preamble of a stream: version, units, history, notes.
std::string format_preamble(const Stream& stream) {
  std::string out = "# libsection-stream " + std::to_string(stream_version) + "\n";
  out += "# units " + one_line(stream.units) + "\n";
  for (const auto& h : stream.history) out += "# history " + one_line(h) + "\n";
  for (const auto& n : stream.notes) out += "# " + one_line(n) + "\n";
  return out;
}

// The stream's text: the preamble, then issues and tables; for a part (`part_line` not
// empty), that line and the part's notes instead of the preamble.
FormattedStream format_parts(const Stream& stream, const std::string& part_line = "") {
  // Pieces are collected first and viewed at the end (a growing vector moves its strings).
  struct Piece {
    std::string text;
    std::string_view kept;  // source rows, when not empty
  };
  std::vector<Piece> pieces(1);
  std::string* out = &pieces.back().text;
  if (part_line.empty()) {
    *out += format_preamble(stream);
  } else {
    *out += part_line;
    for (const auto& n : stream.notes) *out += "# " + one_line(n) + "\n";
  }
  for (const auto& i : stream.issues)
    *out += "# issue section=" + std::to_string(i.section) + " loop=" + std::to_string(i.loop) +
            " stage=" + one_line(i.stage.empty() ? "unknown" : i.stage) + " message=" + one_line(i.message) + "\n";
  for (const auto& t : stream.tables) {
    *out += "# table " + t.name + "\n";
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      if (c) *out += ',';
      *out += t.columns[c];
    }
    *out += '\n';
    const std::size_t cols = t.columns.size();
    if (cols == 0) continue;
    if (unchanged_since_read(t)) {
      const std::string_view rows = t.source->rows;
      pieces.push_back({{}, rows});
      pieces.emplace_back();
      out = &pieces.back().text;
      if (!rows.empty() && rows.back() != '\n') *out += '\n';
      continue;
    }
    for (std::size_t i = 0; i < t.values.size(); ++i)
      if (!std::isfinite(t.values[i]))
        throw Error("pipe: refusing to write a non-finite value in table '" + t.name + "' row " +
                    std::to_string(i / cols) + " column '" + t.columns[i % cols] + "'");
    // Large tables are formatted in pieces of rows by all cores, kept in order.
    const std::size_t rows = t.values.size() / cols;
    const std::size_t parts = std::max<std::size_t>(1, std::min<std::size_t>(64, rows * cols / 32768));
    std::vector<std::string> piece(parts);
    detail::parallel_for(parts, 0, [&](std::size_t k) { piece[k] = format_rows(t, rows * k / parts, rows * (k + 1) / parts); });
    for (auto& s : piece) pieces.push_back({std::move(s), {}});
    pieces.emplace_back();
    out = &pieces.back().text;
    char buf[32];
    for (std::size_t i = rows * cols; i < t.values.size(); ++i) {  // a partial last row (not made by add_row)
      out->append(buf, put_number(buf, t.values[i]));
      *out += (i % cols == cols - 1) ? '\n' : ',';
    }
  }
  FormattedStream f;
  f.formatted.reserve(pieces.size());
  for (auto& p : pieces) {
    if (!p.kept.empty()) {
      f.parts.push_back(p.kept);
    } else if (!p.text.empty()) {
      f.formatted.push_back(std::move(p.text));
      f.parts.emplace_back(f.formatted.back());
    }
  }
  return f;
}

// Writes the parts to `f`; false on a short write.
bool write_parts(std::FILE* f, const FormattedStream& s) {
  for (const auto& p : s.parts)
    if (std::fwrite(p.data(), 1, p.size(), f) != p.size()) return false;
  return true;
}

}  // namespace

std::string format_stream(const Stream& stream) {
  const FormattedStream f = format_parts(stream);
  std::string out;
  out.reserve(f.size());
  for (const auto& p : f.parts) out += p;
  return out;
}

std::string format_csv(const Table& table) {
  std::string out;
  for (std::size_t c = 0; c < table.columns.size(); ++c) out += (c ? "," : "") + table.columns[c];
  out += '\n';
  for (std::size_t r = 0; r < table.rows(); ++r) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      if (c) out += ',';
      out += format_number(table.at(r, c));
    }
    out += '\n';
  }
  return out;
}

std::string read_file(const std::string& path) {
  // Block reads for files and standard input alike (a character iterator over std::cin
  // took twice as long as parsing the stream).
  const bool in = path == "-";
  std::FILE* f = in ? stdin : std::fopen(path.c_str(), "rb");
  if (!f) throw Error(path + ": cannot open: " + std::strerror(errno));
  // Straight into the string, doubling it when full (no copy out of a separate buffer).
  std::string data(std::size_t(1) << 20, '\0');
  std::size_t size = 0, n;
  while (true) {
    if (size == data.size()) data.resize(2 * data.size());
    if ((n = std::fread(&data[size], 1, data.size() - size, f)) == 0) break;
    size += n;
  }
  data.resize(size);
  const bool bad = std::ferror(f);
  if (!in) std::fclose(f);
  if (bad) throw Error(in ? std::string("cannot read standard input") : path + ": read error");
  return data;
}

void write_file(const std::string& path, const std::string& bytes) {
  if (path == "-") {
    std::cout.flush();  // anything written through std::cout before goes first
    const std::size_t n = std::fwrite(bytes.data(), 1, bytes.size(), stdout);
    if (n != bytes.size() || std::fflush(stdout) != 0) throw Error("cannot write standard output");
    return;
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw Error(path + ": cannot open for writing: " + std::strerror(errno));
  const std::size_t n = std::fwrite(bytes.data(), 1, bytes.size(), f);
  const bool bad = n != bytes.size() || std::fclose(f) != 0;
  if (bad) throw Error(path + ": write error");
}

Stream read_stream(const std::string& path) {
  return parse_stream(std::make_shared<const std::string>(read_file(path)), path == "-" ? "<stdin>" : path);
}

void write_stream(const std::string& path, const Stream& stream) {
  // Formatted whole before the first byte is written; the parts are written as they are
  // (no copy into one string).
  const FormattedStream f = format_parts(stream);
  if (path == "-") {
    std::cout.flush();  // anything written through std::cout before goes first
    if (!write_parts(stdout, f) || std::fflush(stdout) != 0) throw Error("cannot write standard output");
    return;
  }
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (!out) throw Error(path + ": cannot open for writing: " + std::strerror(errno));
  const bool bad = !write_parts(out, f);
  if (std::fclose(out) != 0 || bad) throw Error(path + ": write error");
}

StreamWriter::StreamWriter(const std::string& path, const Stream& head) : path_(path) {
  if (path == "-") {
    std::cout.flush();  // anything written through std::cout before goes first
    file_ = stdout;
    // A pipe that holds a whole part: the next tool reads it in one go, and this one
    // writes it without waiting (Linux; elsewhere, or when refused, the default stands).
#ifdef F_SETPIPE_SZ
    struct stat st {};
    if (::fstat(fileno(stdout), &st) == 0 && S_ISFIFO(st.st_mode)) ::fcntl(fileno(stdout), F_SETPIPE_SZ, 1 << 20);
#endif
  } else {
    // A regular file (or a new one) is written under a temporary name and renamed when
    // whole; anything else (/dev/null, a named pipe) is written as it is.
    struct stat st {};
    const bool special = ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
    if (!special) temporary_ = path + ".partial";
    file_ = std::fopen(special ? path.c_str() : temporary_.c_str(), "wb");
    if (!file_ && !special) {
      // A directory that takes no new file may still let the file itself be written.
      temporary_.clear();
      file_ = std::fopen(path.c_str(), "wb");
    }
    if (!file_) throw Error(path + ": cannot open for writing: " + std::strerror(errno));
  }
  write(format_preamble(head));
}

StreamWriter::~StreamWriter() {
  if (file_ && file_ != stdout) {
    std::fclose(file_);
    if (!temporary_.empty()) std::remove(temporary_.c_str());
  }
}

void StreamWriter::write(std::string_view bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    throw Error(path_ == "-" ? std::string("cannot write standard output") : path_ + ": write error");
}

void StreamWriter::part(const std::string& label, const Stream& part) {
  if (finished_) throw Error("pipe: a part written after '# end'");
  const FormattedStream f = format_parts(part, "# part " + one_line(label) + "\n");
  for (const auto& p : f.parts) write(p);
  if (std::fflush(file_) != 0)
    throw Error(path_ == "-" ? std::string("cannot write standard output") : path_ + ": write error");
}

void StreamWriter::finish() {
  if (finished_) return;
  write("# end\n");
  if (file_ == stdout) {
    if (std::fflush(stdout) != 0) throw Error("cannot write standard output");
  } else {
    const bool bad = std::fclose(file_) != 0;
    file_ = nullptr;
    if (bad || (!temporary_.empty() && std::rename(temporary_.c_str(), path_.c_str()) != 0)) {
      if (!temporary_.empty()) std::remove(temporary_.c_str());
      throw Error(path_ + ": write error");
    }
  }
  finished_ = true;
}

namespace {

// Reads a stream line by line from a file or standard input, in blocks.
class LineReader {
public:
  explicit LineReader(const std::string& path) : name_(path == "-" ? "<stdin>" : path) {
    file_ = path == "-" ? stdin : std::fopen(path.c_str(), "rb");
    if (!file_) throw Error(path + ": cannot open: " + std::strerror(errno));
    owned_ = path != "-";
  }
  ~LineReader() {
    if (owned_) std::fclose(file_);
  }
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;
  // The next line with its '\n' (the last may lack it); false at the end.
  bool next(std::string_view& line) {
    while (true) {
      const char* nl =
          end_ > at_ ? static_cast<const char*>(std::memchr(buf_.data() + at_, '\n', end_ - at_)) : nullptr;
      if (nl) {
        const std::size_t n = std::size_t(nl - (buf_.data() + at_)) + 1;
        line = std::string_view(buf_.data() + at_, n);
        at_ += n;
        return true;
      }
      if (eof_) {
        if (at_ == end_) return false;
        line = std::string_view(buf_.data() + at_, end_ - at_);
        at_ = end_;
        return true;
      }
      fill();
    }
  }
  const std::string& name() const { return name_; }

private:
  void fill() {
    // Keep the unfinished line at the front, then read after it.
    const std::size_t keep = end_ - at_;
    if (keep && at_) std::memmove(buf_.data(), buf_.data() + at_, keep);
    at_ = 0;
    end_ = keep;
    if (buf_.size() < keep + block) buf_.resize(std::max(2 * buf_.size(), keep + block));
    const std::size_t got = std::fread(buf_.data() + end_, 1, buf_.size() - end_, file_);
    end_ += got;
    if (got == 0) {
      if (std::ferror(file_)) throw Error(file_ == stdin ? std::string("cannot read standard input") : name_ + ": read error");
      eof_ = true;
    }
  }
  static constexpr std::size_t block = std::size_t(1) << 20;
  std::string name_;
  std::FILE* file_ = nullptr;
  bool owned_ = false, eof_ = false;
  std::vector<char> buf_;
  std::size_t at_ = 0, end_ = 0;
};

// The key of a `# key ...` line ("part", "end", "table", ...), or "" for any other line.
std::string_view key_of(std::string_view line) {
  return line.empty() || line[0] != '#' ? std::string_view{} : meta_line(line).key;
}

bool blank(std::string_view line) { return line.find_first_not_of(" \t\r\n") == std::string_view::npos; }

}  // namespace

void run_stage(const StageRun& run) {
  const int threads = run.threads;
  const auto& stage = run.stage;
  const auto written = [&](const Stream& s) {
    if (run.written) run.written(s);
  };
  const auto& before_end = run.before_end;
  const std::string& history = run.history;
  const std::string& output = run.output;
  LineReader reader(run.input);
  const std::string& source = reader.name();
  // The preamble: the lines before the first `# part`, `# table` or data line.
  std::string head_text, first;
  std::string_view line;
  std::size_t line_no = 0;
  while (reader.next(line)) {
    ++line_no;
    const std::string_view key = key_of(line);
    if (key == "part" || key == "table" || (!blank(line) && line[0] != '#')) {
      first = std::string(line);
      break;
    }
    head_text += line;
  }
  if (key_of(first) != "part") {
    // Not split into parts: the whole stream at once.
    std::string text = std::move(head_text);
    text += first;
    while (reader.next(line)) text += line;
    const std::size_t bom = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;  // parse_stream skips it
    Stream stream = run.other_input && text.compare(bom, 19, "# libsection-stream") != 0
                        ? run.other_input(text, source)
                        : parse_stream(std::make_shared<const std::string>(std::move(text)), source);
    stage(stream, threads);
    stream.history.push_back(history);
    written(stream);
    if (before_end) before_end();
    write_stream(output, stream);
    return;
  }
  Stream head = parse_stream(head_text, source);
  if (!head.issues.empty()) throw Error("pipe: " + source + ": issues before the first '# part'");
  head.history.push_back(history);
  StreamWriter writer(output, head);
  // Parts are staged by the workers as they are read, and written in order by this thread.
  struct Job {
    std::string label;
    std::shared_ptr<const std::string> text;  // kept by the tables passed through (Table::source)
    std::size_t first_line = 0;
    Stream result;
    bool done = false;
  };
  std::deque<Job> jobs;           // read and not yet written, in order (references stay valid)
  std::size_t first_job = 0;      // index of jobs.front()
  std::size_t next_to_stage = 0;  // index of the next job a worker takes
  std::mutex mutex;
  std::condition_variable changed;
  bool input_done = false;
  std::exception_ptr error;
  const std::size_t workers =
      threads > 0 ? std::size_t(threads) : std::max<std::size_t>(1, std::thread::hardware_concurrency());
  const auto work = [&] {
    std::unique_lock<std::mutex> lock(mutex);
    while (true) {
      changed.wait(lock, [&] { return error || next_to_stage < first_job + jobs.size() || input_done; });
      if (error || next_to_stage >= first_job + jobs.size()) return;
      Job& job = jobs[next_to_stage++ - first_job];
      lock.unlock();
      try {
        Stream part = parse_stream_text(*job.text, source, job.text, PartText{true, job.first_line});
        part.units = head.units;
        stage(part, 1);
        job.text = nullptr;
        job.result = std::move(part);
        lock.lock();
        job.done = true;
      } catch (...) {
        lock.lock();
        if (!error) error = std::current_exception();
      }
      changed.notify_all();
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 0; w < workers; ++w) pool.emplace_back(work);
  // Writes the finished parts at the front, in order. With `room`, until fewer than two
  // parts per worker wait (the memory of a pipe stays that of a few sections); with
  // `all`, until every part is written.
  const auto write_done = [&](bool room, bool all) {
    std::unique_lock<std::mutex> lock(mutex);
    while (!error) {
      if (!jobs.empty() && jobs.front().done) {
        Job job = std::move(jobs.front());
        jobs.pop_front();
        ++first_job;
        lock.unlock();
        written(job.result);
        writer.part(job.label, job.result);
        lock.lock();
        continue;
      }
      if (all ? jobs.empty() : !(room && jobs.size() >= 2 * workers)) return;
      changed.wait(lock, [&] { return error || (!jobs.empty() && jobs.front().done); });
    }
  };
  try {
    std::string label = std::string(meta_line(first).rest), text = first;
    std::size_t first_line = line_no;
    bool ended = false;
    // Queues the part read so far; false once a part has failed (no use reading on).
    const auto submit = [&] {
      write_done(true, false);
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (error) return false;
        jobs.push_back(Job{label, std::make_shared<const std::string>(std::move(text)), first_line, {}, false});
      }
      changed.notify_all();
      return true;
    };
    while (reader.next(line)) {
      ++line_no;
      if (ended) {
        if (!blank(line)) fail(source, line_no, "a line after '# end'");
        continue;
      }
      const std::string_view key = key_of(line);
      if (key == "part" || key == "end") {
        if (!submit()) break;
        text.clear();
        first_line = line_no;
        label = std::string(meta_line(line).rest);
        if (key == "end") ended = true;
        if (key == "end" && !label.empty()) fail(source, line_no, "'# end' takes nothing after it");
        if (key == "end") continue;
      }
      text += line;
    }
    bool failed;
    {
      std::lock_guard<std::mutex> lock(mutex);
      failed = bool(error);
    }
    if (!ended && !failed) throw truncated_parts(source);
    write_done(false, true);
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex);
    if (!error) error = std::current_exception();
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    input_done = true;
  }
  changed.notify_all();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  if (before_end) before_end();
  writer.finish();
}

void append_rows(Table& to, const Table& from) {
  if (to.columns.empty() && to.values.empty()) {
    to.name = from.name;
    to.columns = from.columns;
  } else if (to.columns != from.columns) {
    throw Error("pipe: table '" + from.name + "' has other columns than before");
  }
  to.values.insert(to.values.end(), from.values.begin(), from.values.end());
}

namespace {

// Splits on commas or runs of blanks.
std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i == n) break;
    const std::size_t start = i;
    while (i < n && line[i] != ',' && line[i] != ' ' && line[i] != '\t') ++i;
    out.push_back(line.substr(start, i - start));
    while (i < n && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i < n && line[i] == ',') {
      ++i;
      if (i == n) out.push_back(std::string_view{});
    }
  }
  return out;
}

template <class F>
void for_each_line(std::string_view text, F&& f) {
  std::size_t pos = 0, line_no = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    ++line_no;
    std::string_view line = trim(text.substr(pos, end - pos));
    pos = end + 1;
    if (line.empty() || line[0] == '#') continue;
    f(line, line_no);
  }
}

}  // namespace

Table parse_csv(std::string_view text, const std::string& source) {
  Table t;
  t.name = source;
  if (const char* why = detail::text_encoding_problem(text)) throw Error("pipe: " + source + ": " + why);
  detail::skip_bom(text);
  bool header = false;
  for_each_line(text, [&](std::string_view line, std::size_t line_no) {
    const auto fields = split_fields(line);
    if (!header) {
      for (const auto& f : fields) {
        if (trim(f).empty()) fail(source, line_no, "empty column name in the header");
        t.columns.emplace_back(trim(f));
      }
      header = true;
      return;
    }
    if (fields.size() != t.columns.size())
      fail(source, line_no, std::to_string(fields.size()) + " values for " + std::to_string(t.columns.size()) + " columns");
    for (std::size_t c = 0; c < fields.size(); ++c) {
      double v = 0;
      if (!parse_double(trim(fields[c]), v))
        fail(source, line_no, "column '" + t.columns[c] + "': expected a number, found '" + std::string(fields[c].substr(0, 40)) + "'");
      if (!std::isfinite(v)) fail(source, line_no, "column '" + t.columns[c] + "': non-finite value");
      t.values.push_back(v);
    }
  });
  if (!header) throw Error("pipe: " + source + ": empty table (no header row)");
  return t;
}

std::vector<Eigen::Vector2d> parse_profile(std::string_view text, const std::string& source) {
  std::vector<Eigen::Vector2d> points;
  if (const char* why = detail::text_encoding_problem(text)) throw Error("pipe: " + source + ": " + why);
  detail::skip_bom(text);
  bool data = false;
  for_each_line(text, [&](std::string_view line, std::size_t line_no) {
    const auto fields = split_fields(line);
    double x = 0, y = 0;
    const bool numeric = fields.size() >= 2 && parse_double(trim(fields[0]), x) && parse_double(trim(fields[1]), y);
    if (!numeric) {
      if (!data) return;  // a title line
      fail(source, line_no, fields.size() < 2 ? "expected x and y, found one value" : "expected two numbers x, y, found '" + std::string(line.substr(0, 40)) + "'");
    }
    data = true;
    if (!std::isfinite(x) || !std::isfinite(y)) fail(source, line_no, "non-finite coordinate");
    if (std::abs(x) > detail::max_coordinate || std::abs(y) > detail::max_coordinate)
      fail(source, line_no, "coordinate beyond +-1e15 (corrupt file?)");
    points.emplace_back(x, y);
  });
  if (points.empty()) throw Error("pipe: " + source + ": no profile points (expected lines of x y)");
  return points;
}


std::vector<Plane> parse_planes(std::string_view csv, const std::string& source) {
  const Table t = parse_csv(csv, source);
  const char* names[6] = {"origin_x", "origin_y", "origin_z", "normal_x", "normal_y", "normal_z"};
  std::size_t c[6];
  for (int k = 0; k < 6; ++k) {
    const long col = t.find_column(names[k]);
    if (col < 0) throw Error("slice: " + source + ": the planes file needs the column '" + names[k] + "'");
    c[k] = static_cast<std::size_t>(col);
  }
  std::vector<Plane> planes;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    Plane p{{t.at(r, c[0]), t.at(r, c[1]), t.at(r, c[2])}, {t.at(r, c[3]), t.at(r, c[4]), t.at(r, c[5])}};
    if (!(p.normal.norm() > 0))
      throw Error("slice: " + source + ": plane " + std::to_string(r) + " (data row " + std::to_string(r + 1) + ") has a zero normal");
    planes.push_back(p);
  }
  if (planes.empty()) throw Error("slice: " + source + ": no planes");
  return planes;
}

}  // namespace section
