// SPDX-License-Identifier: GPL-3.0-or-later
// The stream formatter: numbers in their shortest round-trip form, tables passed through as
// they were read, large tables formatted in pieces by all cores.
#include "section/io/stream.h"

#include "detail/parallel.h"
#include "io/byte_source.h"
#include "io/shortest_number.h"
#include "io/stream_text.h"
#include "section/error.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <memory>

namespace section {

namespace detail {

namespace {

// Writes v as std::to_chars(double) does (shortest round trip, fixed or scientific,
// whichever is shorter, fixed on a tie). Integers below 100000 in magnitude (ids, counts)
// print in fixed notation, digit by digit, much faster; most others by shortest_number.
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
  if (char* end = shortest_number(p, v)) return end;
  return std::to_chars(p, p + 32, v).ptr;
}

// Text formatted into a buffer of its own: the first `size` bytes.
struct RowsText {
  std::unique_ptr<char[]> bytes;
  std::size_t size = 0;
};

// Rows [r0, r1) of a table's values as text, in a buffer left uninitialised (a string
// zeroed first took a fifth of the formatting's instructions).
RowsText format_rows(const Table& t, std::size_t r0, std::size_t r1) {
  const std::size_t cols = t.columns.size();
  RowsText out{std::unique_ptr<char[]>(new char[(r1 - r0) * cols * 25]), 0};  // a double takes at most 24
  char* p = out.bytes.get();
  const double* v = t.values.data() + r0 * cols;
  for (std::size_t r = r0; r < r1; ++r) {
    for (std::size_t c = 0; c < cols; ++c) {
      p = put_number(p, *v++);
      *p++ = ',';
    }
    p[-1] = '\n';
  }
  out.size = std::size_t(p - out.bytes.get());
  return out;
}

// True when `t` holds what its source text reads as (bit for bit: -0 is not 0).
bool unchanged_since_read(const Table& t) {
  const TableText* src = t.source.get();
  return src && src->columns == t.columns && src->values.size() == t.values.size() &&
         (t.values.empty() ||
          std::memcmp(src->values.data(), t.values.data(), t.values.size() * sizeof(double)) == 0);
}

// The pieces of a stream's text, collected first and viewed at the end (a growing vector
// moves its strings).
class Pieces {
public:
  /// The piece being written.
  std::string& text() { return pieces_.back().text; }
  /// Source rows, written as they are.
  void keep(std::string_view rows) {
    pieces_.push_back({{}, rows, nullptr});
    pieces_.emplace_back();
  }
  /// Rows formatted elsewhere, in order.
  void add(std::vector<RowsText>& formatted) {
    for (auto& s : formatted) {
      const std::string_view rows(s.bytes.get(), s.size);
      pieces_.push_back({{}, rows, std::move(s.bytes)});
    }
    pieces_.emplace_back();
  }
  FormattedStream finish() {
    FormattedStream f;
    f.formatted.reserve(pieces_.size());
    for (auto& p : pieces_) {
      if (p.rows) f.rows.push_back(std::move(p.rows));  // (`kept` views it)
      if (!p.kept.empty()) {
        f.parts.push_back(p.kept);
      } else if (!p.text.empty()) {
        f.formatted.push_back(std::move(p.text));
        f.parts.emplace_back(f.formatted.back());
      }
    }
    return f;
  }

private:
  struct Piece {
    std::string text;
    std::string_view kept;         // source rows or formatted rows, when not empty
    std::unique_ptr<char[]> rows;  // the formatted rows `kept` views
  };
  std::vector<Piece> pieces_ = std::vector<Piece>(1);
};

// A table: its `# table` line and header, then its rows (kept or formatted).
void format_table(const Table& t, Pieces& pieces) {
  std::string* out = &pieces.text();
  *out += "# table " + t.name + "\n";
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    if (c) *out += ',';
    *out += t.columns[c];
  }
  *out += '\n';
  const std::size_t cols = t.columns.size();
  // A partial row was written as it was, and the stream did not read back.
  if (const std::string why = partial_rows(t); !why.empty())
    throw Error("pipe: refusing to write table '" + t.name + "': " + why);
  if (cols == 0) return;
  if (unchanged_since_read(t)) {
    const std::string_view rows = t.source->rows;
    pieces.keep(rows);
    if (!rows.empty() && rows.back() != '\n') pieces.text() += '\n';
    return;
  }
  for (std::size_t i = 0; i < t.values.size(); ++i)
    if (!std::isfinite(t.values[i]))
      throw Error("pipe: refusing to write a non-finite value in table '" + t.name + "' row " +
                  std::to_string(i / cols) + " column '" + t.columns[i % cols] + "'");
  // Large tables are formatted in pieces of rows by all cores, kept in order.
  const std::size_t rows = t.values.size() / cols;
  const std::size_t parts = std::max<std::size_t>(1, std::min<std::size_t>(64, rows * cols / 32768));
  std::vector<RowsText> piece(parts);
  detail::parallel_for(
      parts, 0, [&](std::size_t k) { piece[k] = format_rows(t, rows * k / parts, rows * (k + 1) / parts); });
  pieces.add(piece);
}

// A note's line; one whose first word is a keyword of the format ("end", "table x", ...)
// would be read back as that line, not as a note.
std::string note_line(const std::string& note) {
  const std::string text = one_line(note);
  const std::string key = text.substr(0, text.find(' '));
  for (const char* reserved : {"libsection-stream", "units", "history", "issue", "table", "part", "end"})
    if (key == reserved)
      throw Error("pipe: refusing to write the note '" + text.substr(0, 40) + "': it would read as a '# " +
                  key + "' line");
  return "# " + text + "\n";
}

}  // namespace

std::string format_preamble(const Stream& stream) {
  std::string out = "# libsection-stream " + std::to_string(stream_version) + "\n";
  out += "# units " + one_line(stream.units) + "\n";
  for (const auto& h : stream.history) out += "# history " + one_line(h) + "\n";
  for (const auto& n : stream.notes) out += note_line(n);
  return out;
}

FormattedStream format_parts(const Stream& stream, const std::string& part_line) {
  Pieces pieces;
  std::string& out = pieces.text();
  if (part_line.empty()) {
    out += format_preamble(stream);
  } else {
    out += part_line;
    for (const auto& n : stream.notes) out += note_line(n);
  }
  for (const auto& i : stream.issues)
    out += "# issue section=" + std::to_string(i.section) + " loop=" + std::to_string(i.loop) +
           " stage=" + one_line(i.stage.empty() ? "unknown" : i.stage) + " message=" + one_line(i.message) +
           "\n";
  for (const auto& t : stream.tables) format_table(t, pieces);
  return pieces.finish();
}

}  // namespace detail

std::string format_stream(const Stream& stream) {
  const detail::FormattedStream f = detail::format_parts(stream);
  std::string out;
  out.reserve(f.size());
  for (const auto& p : f.parts) out += p;
  return out;
}

void write_stream(const std::string& path, const Stream& stream) {
  // Formatted whole before the first byte is written; the parts are written as they are
  // (no copy into one string).
  const detail::FormattedStream f = detail::format_parts(stream);
  detail::ByteSink out(path, "");
  for (const auto& p : f.parts) out.write(p);
  out.close();
}

}  // namespace section
