// SPDX-License-Identifier: GPL-3.0-or-later
// The stream parser: `#` lines, table headers and numeric rows, with the line of any error.
#include "section/io/stream.h"

#include "detail/parallel.h"
#include "io/plain_number.h"
#include "io/stream_text.h"
#include "io/text.h"
#include "section/error.h"
#include "section/io/file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace section {

namespace detail {

namespace {

std::vector<std::string> split_header(std::string_view line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.emplace_back(trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
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
    if (at == std::string_view::npos) stream_fail(source, line, "issue line without '" + needle + "'");
    std::string_view value = rest.substr(at + needle.size());
    if (key != "message") value = value.substr(0, value.find(' '));
    return value;
  };
  const auto to_int = [&](std::string_view s) {
    int v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
      stream_fail(source, line, "issue line with a bad id '" + std::string(s) + "'");
    return v;
  };
  issue.section = to_int(take("section"));
  issue.loop = to_int(take("loop"));
  issue.stage = std::string(take("stage"));
  issue.message = std::string(take("message"));
  return issue;
}

// A cell as a number (false when it is none), in the writers' form without from_chars (the
// same double, io/plain_number.h); the text from `readable` on may be read.
inline bool cell_number(const char* readable, std::string_view cell, double& value) {
  const char* const end = cell.data() + cell.size();
  const char* const read = cell.empty() ? nullptr : plain_number(readable, cell.data(), end, value);
  return (read && read == end) || parse_double(cell, value);
}

// What a row's ids must be: per column 0 (not an id), 1 (an id: an integer, 0 or more), 2
// (the section id, equal to `section` in a part of a stream split into parts) or `unread`
// (not an id, its value never read: plain_row checks its form and keeps NaN).
struct IdRules {
  static constexpr char unread = 3;
  std::vector<char> column;
  double section = -1;      // the part's section, -1 outside parts
  std::size_t leading = 0;  // the first columns, section and loop, that most rows repeat (not all columns)
  // True when `value` in column `col` is a valid id there.
  bool ok(std::size_t col, double value) const {
    if (!column[col] || column[col] == unread) return true;
    // A whole number in [0, 2^31): in that range the cast is exact (std::floor was slower).
    if (!(value >= 0 && value <= 2147483647.0) || double(std::int64_t(value)) != value) return false;
    return column[col] != 2 || section < 0 || value == section;
  }
};

// One data row of `columns` cells appended to `out`; false on anything the line-by-line
// parse refuses (it then finds and names the problem). The text from `readable` on may be read.
bool parse_row(const char* readable, std::string_view line, const IdRules& ids, std::vector<double>& out) {
  const std::size_t columns = ids.column.size();
  std::size_t start = 0, col = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view cell =
        trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start));
    if (col == columns) return false;
    double value = 0;
    if (!cell_number(readable, cell, value) || !std::isfinite(value) || std::abs(value) > max_coordinate)
      return false;
    if (!ids.ok(col, value)) return false;
    out.push_back(value);
    ++col;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return col == columns;
}

constexpr std::size_t plain_row_most = 32;  // the widest row plain_row reads (the others: parse_row)

// The leading ids (IdRules::leading) of the last row read and their text, to be taken again
// where the next row starts with the same bytes (the section and loop of most rows).
struct Leading {
  const char* row = nullptr;
  std::uint64_t mask = 0;  // the bytes of their text ("0,12,"), at most 8
  std::size_t length = 0;
  double value[2] = {0, 0};
};

// A row at `p` in the form the writers give (cells plain_number, ids 1 to 9 digits, ','
// between them, '\n' or `end` after them) into `row`: the end of its line, or nullptr for
// any other row (then left to parse_row; `row` holds nothing then). The text from `readable`
// on may be read.
inline const char* plain_row(const char* readable, const char* p, const char* end, const IdRules& ids,
                             Leading& leading, double* row) {
  const std::size_t columns = ids.column.size();
  if (columns == 0 || columns > plain_row_most) return nullptr;
  const char* const kind = ids.column.data();
  const char* const start = p;
  std::size_t col = 0;
  if (leading.length && end - p >= 8) {
    std::uint64_t now, before;
    std::memcpy(&now, p, 8);
    std::memcpy(&before, leading.row, 8);
    if (((now ^ before) & leading.mask) == 0) {  // the same text: the same (valid) ids
      for (; col < ids.leading; ++col) row[col] = leading.value[col];
      p += leading.length;
    }
  }
  for (;; ++col) {
    if (!kind[col]) {
      double value = 0;
      p = plain_number(readable, p, end, value);
      if (!p || std::abs(value) > max_coordinate) return nullptr;
      row[col] = value;
    } else if (kind[col] == IdRules::unread) {
      // Never read: its form alone, which every such cell of a valid row has. (NaN cannot
      // be written: the table is passed on as its text, or refused.)
      p = plain_number_end(p, end);
      if (!p) return nullptr;
      row[col] = std::numeric_limits<double>::quiet_NaN();
    } else {
      // An id as an integer: below 10^9, so a valid id and exact as a double, without the
      // checks of a double that could be one.
      const char* const first = p;
      std::uint32_t id = 0;
      while (p < end && static_cast<unsigned>(*p - '0') < 10) id = 10 * id + std::uint32_t(*p++ - '0');
      if (p == first || p - first > 9) return nullptr;
      row[col] = double(id);
      if (kind[col] == 2 && ids.section >= 0 && row[col] != ids.section) return nullptr;
    }
    if (col + 1 == columns) {
      if (p != end && *p++ != '\n') return nullptr;
      break;
    }
    if (p == end || *p++ != ',') return nullptr;
    if (col + 1 == ids.leading && p - start <= 8) {
      leading.row = start;
      leading.length = std::size_t(p - start);
      leading.mask = leading.length == 8 ? ~std::uint64_t(0) : (std::uint64_t(1) << (8 * leading.length)) - 1;
      std::copy(row, row + ids.leading, leading.value);
    }
  }
  return p;
}

// The data rows of `text` (whole lines, blank ones skipped) into `out`; false when any row
// is refused. Rows in the writers' form are read in one pass, their line ends with them,
// gathered on the stack and appended some at a time: one check of the vector's room for
// many rows, not one a row.
bool parse_rows(std::string_view text, const IdRules& ids, std::vector<double>& out) {
  const char* p = text.data();
  const char* const end = p + text.size();
  constexpr std::size_t room = 32 * plain_row_most;
  double rows[room];
  std::size_t held = 0;  // values in `rows`
  const std::size_t columns = ids.column.size();
  Leading leading;
  const auto append = [&] {
    out.insert(out.end(), rows, rows + held);
    held = 0;
  };
  while (p < end) {
    if (const char* next =
            plain_row(text.data(), p, end, ids, leading, rows + held)) {  // (room for a row after `held`)
      p = next;
      held += columns;
      if (held + columns > room) append();
      continue;
    }
    append();  // (rows in order)
    const void* nl = std::memchr(p, '\n', std::size_t(end - p));
    const char* const line_end = nl ? static_cast<const char*>(nl) : end;
    std::string_view line(p, std::size_t(line_end - p));
    p = nl ? line_end + 1 : end;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (trim(line).empty()) continue;
    if (!parse_row(text.data(), line, ids, out)) return false;
  }
  append();
  return true;
}

// Parses a stream's text line by line (a table's rows in pieces by all cores when they are
// many); the state of the parse is the table being read and what the lines before declared.
class StreamParser {
public:
  StreamParser(std::string_view text, const std::string& source,
               const std::shared_ptr<const std::string>& owner, const PartText& part)
      : text_(text),
        source_(source),
        owner_(owner),
        part_(part),
        seen_version_(part.is_part),
        line_no_(part.first_line - 1) {}

  Stream parse();

private:
  [[noreturn]] void fail(const std::string& what) const { stream_fail(source_, line_no_, what); }
  void meta(std::string_view line);
  void table(std::string_view rest);
  void header(std::string_view line);
  void block();
  bool parse_pieces(std::string_view block, std::size_t parts, const IdRules& ids);
  void keep_source(std::string_view block);
  void row(std::string_view line);

  std::string_view text_;
  const std::string& source_;
  const std::shared_ptr<const std::string>& owner_;
  const PartText part_;
  Stream stream_;
  Table* current_ = nullptr;  // the table whose rows come
  bool expect_header_ = false;
  bool seen_version_;
  std::size_t line_no_;
  // Parts (docs/FORMAT.md): a table may come again in a later part, with the same header.
  std::size_t parts_ = 0;
  std::size_t units_line_ = 0;  // the line of the '# units' seen (0: none)
  bool ended_ = false;
  std::vector<std::string> in_part_;            // tables seen in the current part
  std::vector<std::string> continued_columns_;  // header a continued table must repeat (empty: a new table)
  std::size_t pos_ = 0;
  std::vector<double> row_;
  IdRules ids_;  // the ids of the current table's columns
};

Stream StreamParser::parse() {
  if (const char* why = text_encoding_problem(text_)) throw Error("pipe: " + source_ + ": " + why);
  if (!part_.is_part) skip_bom(text_);
  if (text_.empty()) throw Error("pipe: " + source_ + ": the stream is empty");
  while (pos_ < text_.size()) {
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_no_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (trim(line).empty()) continue;
    if (line[0] == '#') {
      meta(line);
      continue;
    }
    if (!seen_version_) fail("not a libsection stream (the first line must be '# libsection-stream 1')");
    if (ended_) fail("a line after '# end'");
    if (!current_) fail("a data row outside any table (missing '# table NAME')");
    if (expect_header_) {
      header(line);
      block();
    } else {
      row(line);
    }
  }
  if (!seen_version_) throw Error("pipe: " + source_ + ": the stream is empty");
  if (expect_header_)
    throw Error("pipe: " + source_ + ": table '" + current_->name +
                "' has no header row (truncated stream?)");
  if (parts_ > 0 && !ended_ && !part_.is_part) throw truncated_parts(source_);
  return std::move(stream_);
}

void StreamParser::meta(std::string_view line) {
  const auto [key, rest, body] = meta_line(line);
  if (expect_header_) fail("table '" + current_->name + "' has no header row");
  if (ended_) fail("a line after '# end'");
  if (!seen_version_) {
    if (key != "libsection-stream")
      fail("not a libsection stream (the first line must be '# libsection-stream 1')");
    if (rest != std::to_string(stream_version))
      fail("stream version '" + std::string(rest) + "' is not supported (this build reads version " +
           std::to_string(stream_version) + ")");
    seen_version_ = true;
    return;
  }
  current_ = nullptr;
  if (key == "table") {
    table(rest);
  } else if (key == "part") {
    if (part_.is_part && parts_ > 0) fail("two parts in one");
    ++parts_;
    in_part_.clear();
    // A part is one section's: its label is the section id its rows and issues carry.
    int id = -1;
    if (!parse_integer(rest, id) || id < 0) fail("part label '" + printable(rest) + "' is not a section id");
    ids_.section = id;
  } else if (key == "end") {
    if (!rest.empty()) fail("'# end' takes nothing after it");
    ended_ = true;
  } else if (key == "units") {
    if (rest.empty()) fail("'# units' without a unit");
    // One unit a stream: a second line changed every length read before it, or after it.
    if (part_.is_part || parts_ > 0)
      fail("'# units' in a part: a stream has one unit, said before its first part");
    if (units_line_ > 0 && rest != stream_.units)
      fail("a second '# units' line (" + printable(rest) + "; line " + std::to_string(units_line_) +
           " said " + stream_.units + "): a stream has one unit");
    units_line_ = line_no_;
    stream_.units = std::string(rest);
  } else if (key == "history") {
    stream_.history.emplace_back(rest);
  } else if (key == "issue") {
    stream_.issues.push_back(parse_issue(rest, source_, line_no_));
    const SectionIssue& issue = stream_.issues.back();
    if (issue.section < 0 || issue.loop < -1) fail("issue line with a negative id");
    if (ids_.section >= 0 && issue.section != ids_.section)
      fail("an issue of section " + std::to_string(issue.section) + " in the part of section " +
           format_number(ids_.section));
  } else {
    stream_.notes.emplace_back(body);
  }
}

// `# table NAME`: a new table, or the same table in a later part (its rows follow those before).
void StreamParser::table(std::string_view rest) {
  if (rest.empty()) fail("'# table' without a name");
  const std::string name(rest);
  if (std::find(in_part_.begin(), in_part_.end(), name) != in_part_.end() ||
      (parts_ == 0 && stream_.find(name)))
    fail("table '" + name + "' appears twice" + (parts_ ? " in a part" : ""));
  in_part_.push_back(name);
  continued_columns_.clear();
  if (Table* earlier = stream_.find(name)) {
    continued_columns_ = earlier->columns;
    earlier->source = nullptr;  // its text is no longer one piece
    current_ = earlier;
  } else {
    stream_.tables.push_back(Table{name, {}, {}});
    current_ = &stream_.tables.back();
  }
  expect_header_ = true;
}

void StreamParser::header(std::string_view line) {
  const std::vector<std::string> names = split_header(line);
  if (!continued_columns_.empty() && names != continued_columns_)
    fail("table '" + current_->name + "' has other columns than in the parts before");
  current_->columns = names;
  for (const auto& c : current_->columns)
    if (c.empty()) fail("empty column name in the header of table '" + current_->name + "'");
  ids_.column.assign(current_->columns.size(), 0);
  for (std::size_t c = 0; c < current_->columns.size(); ++c) {
    const std::string& n = current_->columns[c];
    if (std::find(current_->columns.begin(), current_->columns.begin() + long(c), n) !=
        current_->columns.begin() + long(c))
      fail("column '" + n + "' appears twice in the header of table '" + current_->name + "'");
    ids_.column[c] = n == "section" ? 2 : is_id_column(n) ? 1 : 0;
  }
  if (part_.unread)
    for (std::size_t c = 0; c < names.size(); ++c)
      if (!ids_.column[c] && std::find(part_.unread->begin(), part_.unread->end(),
                                       std::make_pair(current_->name, names[c])) != part_.unread->end())
        ids_.column[c] = IdRules::unread;
  ids_.leading = 0;
  while (ids_.leading < std::min<std::size_t>(2, names.size() - 1) &&
         (names[ids_.leading] == "section" || names[ids_.leading] == "loop"))
    ++ids_.leading;
  expect_header_ = false;
}

// The table's data rows run to the next line starting with '#': a block of a few kB and up
// (a section's table in a stream split into parts) is parsed in pieces by all cores,
// appended in order. A piece that refuses a row leaves the block to the line-by-line parse,
// whose error names the line.
void StreamParser::block() {
  const std::size_t block_start =
      std::min(pos_, text_.size());  // pos is past the end after a last line without '\n'
  // The first '#' that starts a line (one may stand inside a bad row).
  std::size_t block_end = block_start;
  while (block_end < text_.size() && text_[block_end] != '#') {
    const std::size_t hash = text_.find('#', block_end);
    if (hash == std::string_view::npos) {
      block_end = text_.size();
    } else if (text_[hash - 1] == '\n') {
      block_end = hash;
    } else {
      const std::size_t nl = text_.find('\n', hash);
      block_end = nl == std::string_view::npos ? text_.size() : nl + 1;
    }
  }
  const std::string_view block = text_.substr(block_start, block_end - block_start);
  if (block.size() < (std::size_t(1) << 12)) return;
  const std::size_t lines = count_lines(block) + (block.back() != '\n' ? 1 : 0);
  std::vector<double>& values = current_->values;
  const std::size_t before = values.size(), need = before + lines * current_->columns.size();
  if (values.capacity() < need) values.reserve(std::max(need, 2 * values.capacity()));  // (later parts)
  const std::size_t parts =
      part_.threads == 1 ? 1 : std::max<std::size_t>(1, std::min<std::size_t>(64, block.size() >> 17));
  // Cells never read are left undecoded only in rows kept as text, written back as they came.
  const bool keep = continued_columns_.empty() && block.find('\r') == std::string_view::npos;
  IdRules decoded;
  const IdRules* ids = &ids_;
  if (!keep && std::count(ids_.column.begin(), ids_.column.end(), IdRules::unread)) {
    decoded = ids_;
    std::replace(decoded.column.begin(), decoded.column.end(), IdRules::unread, char(0));
    ids = &decoded;
  }
  if (parts == 1 ? !parse_rows(block, *ids, values) : !parse_pieces(block, parts, *ids)) {
    values.resize(before);
    return;
  }
  if (keep) keep_source(block);
  line_no_ += lines;
  pos_ = block_end;
}

// The rows of `block` in `parts` pieces, parsed by several cores and appended in order.
bool StreamParser::parse_pieces(std::string_view block, std::size_t parts, const IdRules& ids) {
  std::vector<std::size_t> cut(parts + 1, 0);
  cut[parts] = block.size();
  for (std::size_t k = 1; k < parts; ++k) {
    const std::size_t at = block.find('\n', std::max(cut[k - 1], block.size() * k / parts));
    cut[k] = at == std::string_view::npos ? block.size() : at + 1;
  }
  std::vector<std::vector<double>> piece(parts);
  std::vector<char> ok(parts, 0);
  detail::parallel_for(parts, part_.threads, [&](std::size_t k) {
    piece[k].reserve((cut[k + 1] - cut[k]) / 8);
    ok[k] = parse_rows(block.substr(cut[k], cut[k + 1] - cut[k]), ids, piece[k]);
  });
  if (!std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; })) return false;
  for (const auto& v : piece) current_->values.insert(current_->values.end(), v.begin(), v.end());
  return true;
}

// The rows of a new table kept to be written back as they are (Table::source); block() keeps
// none with '\r' line ends, which the written stream does not use.
void StreamParser::keep_source(std::string_view block) {
  auto kept = std::make_shared<TableText>();
  if (owner_) {
    kept->text = owner_;
    kept->rows = block;
  } else {
    kept->text = std::make_shared<const std::string>(block);
    kept->rows = *kept->text;
  }
  kept->columns = current_->columns;
  kept->values = current_->values;
  current_->source = std::move(kept);
}

void StreamParser::row(std::string_view line) {
  row_.clear();
  std::size_t start = 0;
  std::size_t col = 0;
  const std::string& table = current_->name;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view cell =
        trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start));
    ++col;
    if (col > current_->columns.size())
      fail("more values than the " + std::to_string(current_->columns.size()) + " columns of table '" +
           table + "'");
    const auto bad = [&](const std::string& what) {
      fail("column '" + current_->columns[col - 1] + "' of table '" + table + "': " + what);
    };
    const auto text = [&] { return std::string(cell.substr(0, 40)); };
    double value = 0;
    if (!cell_number(text_.data(), cell, value)) bad("expected a number, found '" + text() + "'");
    if (!std::isfinite(value)) bad("non-finite value '" + text() + "'");
    if (std::abs(value) > max_coordinate) bad("value " + text() + " is beyond +-1e15 (corrupt stream?)");
    // Ids become ints in every stage: a fraction or a value beyond int would be cast silently.
    if (!ids_.ok(col - 1, value)) {
      if (value != std::floor(value) || std::abs(value) > 2147483647.0)
        bad("'" + text() + "' is not an integer id");
      if (value < 0) bad("'" + text() + "' is a negative id");
      bad("section " + text() + " in the part of section " + format_number(ids_.section) +
          " (a part holds its own section only)");
    }
    row_.push_back(value);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (row_.size() != current_->columns.size())
    fail(std::to_string(row_.size()) + " values for the " + std::to_string(current_->columns.size()) +
         " columns of table '" + table + "' (truncated line?)");
  current_->values.insert(current_->values.end(), row_.begin(), row_.end());
}

}  // namespace

Stream parse_stream_text(std::string_view text, const std::string& source,
                         const std::shared_ptr<const std::string>& owner, const PartText& part) {
  return StreamParser(text, source, owner, part).parse();
}

}  // namespace detail

Stream parse_stream(std::string_view text, const std::string& source) {
  return detail::parse_stream_text(text, source, nullptr);
}

Stream parse_stream(std::shared_ptr<const std::string> text, const std::string& source) {
  if (!text) throw Error("pipe: " + source + ": no text");
  return detail::parse_stream_text(*text, source, text);
}

Stream read_stream(const std::string& path) {
  return parse_stream(std::make_shared<const std::string>(read_file(path)), path == "-" ? "<stdin>" : path);
}

}  // namespace section
