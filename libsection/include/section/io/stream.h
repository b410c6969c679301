// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/stream.h
/// The pipe stream that `slice | smooth | fitspline | camber` pass along: named numeric
/// tables plus metadata, written as CSV with `#` lines. docs/FORMAT.md is the reference.
/// This module is the only place where the stream is parsed or formatted.
#include <Eigen/Core>

#include <cstddef>
#include <cstdio>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <string_view>
#include <string>
#include <utility>
#include <vector>

namespace section {

namespace detail {
class ByteSink;
}

/// The text a table's rows were read from, and what they read as (see Table::source).
struct TableText {
  std::shared_ptr<const std::string> text;  ///< the text the rows lie in
  std::string_view rows;                    ///< the data lines as they came, a part of `text`
  std::vector<std::string> columns;         ///< the columns they were read under
  std::vector<double> values;               ///< the numbers they gave
};

/// One named table: a header of column names and numeric rows (row-major).
struct Table {
  Table() = default;
  /// A table made in memory (no source text).
  Table(std::string table_name, std::vector<std::string> column_names, std::vector<double> row_values = {})
      : name(std::move(table_name)), columns(std::move(column_names)), values(std::move(row_values)) {}

  std::string name;                  ///< e.g. "points"
  std::vector<std::string> columns;  ///< column names, in order
  std::vector<double> values;        ///< rows() * columns.size() numbers, row-major
  /// Set by parse_stream on tables of a few kB and up: format_stream writes `rows` back
  /// as they came while columns and values are still those read, so that a stage passing
  /// a table through does not format it again (the same numbers, in less time). Null for
  /// tables made in memory; a changed table is formatted from its values.
  std::shared_ptr<const TableText> source;

  /// Number of rows.
  std::size_t rows() const { return columns.empty() ? 0 : values.size() / columns.size(); }
  /// Index of a column; throws section::Error `pipe: table 'T' has no column 'C'`.
  std::size_t column(const std::string& column_name) const;
  /// Index of a column, or -1 when absent.
  long find_column(const std::string& column_name) const;
  /// Value at a row and a column index (see column()); unchecked.
  double at(std::size_t row, std::size_t col) const { return values[row * columns.size() + col]; }
  /// Appends one row; it must have columns.size() values.
  void add_row(std::initializer_list<double> row);
  void add_row(const std::vector<double>& row);
};

/// A failure of one section (or one loop of it) at one stage; the others go on.
struct SectionIssue {
  int section = -1;     ///< section id
  int loop = -1;        ///< loop id, -1 for the whole section
  std::string stage;    ///< tool or stage that failed, e.g. "smooth"
  std::string message;  ///< what went wrong
};

/// The whole stream.
struct Stream {
  std::string units = "mm";          ///< length unit of every coordinate
  std::vector<std::string> history;  ///< one line per tool that wrote the stream
  std::vector<std::string> notes;    ///< free `# key value` lines kept as they came
  std::vector<SectionIssue> issues;  ///< per-section failures so far
  std::vector<Table> tables;         ///< tables in stream order

  /// The table named `name`, or nullptr.
  const Table* find(const std::string& name) const;
  Table* find(const std::string& name);
  /// The table named `name`; throws section::Error `pipe: the stream has no 'name' table
  /// (produced by TOOL)` when absent.
  const Table& get(const std::string& name, const std::string& produced_by) const;
  /// Replaces the table of the same name, or appends it.
  void put(Table table);
  /// Removes a table if present.
  void erase(const std::string& name);
  /// True when a section (any loop) has an issue recorded.
  bool failed(int section, int loop = -1) const;
};

/// Current format version written in the first line (`# libsection-stream 1`).
constexpr int stream_version = 1;

/// Parses a stream; `source` (a file name or "<stdin>") is used in error messages, which
/// carry the line number. Throws section::Error on any malformed content.
Stream parse_stream(std::string_view text, const std::string& source);

/// As above; the tables' source rows (Table::source) stay in `text` instead of copies.
Stream parse_stream(std::shared_ptr<const std::string> text, const std::string& source);

/// Reads a stream from `path` ("-" = standard input).
Stream read_stream(const std::string& path);

/// Formats a stream; numbers use the shortest form that round-trips.
std::string format_stream(const Stream& stream);

/// Writes a stream to `path` ("-" = standard output) once it is all formatted, so that a
/// failure before this call leaves no partial output.
void write_stream(const std::string& path, const Stream& stream);

/// Writes a stream split into parts as they come (docs/FORMAT.md, "Parts"): the preamble
/// (version, units, history, notes) at once, each part when given, and the closing
/// `# end` at finish(), so that the next tool of a pipe can work on a part while this one
/// makes the next. Standard output is written as it goes; a file is written under a unique
/// temporary name in its directory (`FILE.XXXXXX.partial`, created anew) and renamed at
/// finish(), so that a failure or a signal leaves no file and two runs do not mix their
/// bytes; a path that is not a regular file (/dev/null, a named pipe) is written as it
/// goes. A stream that is not finished lacks `# end`, and every reader refuses it.
class StreamWriter {
public:
  /// Opens `path` ("-" = standard output) and writes the preamble of `head` (its tables,
  /// issues and notes are not written). Throws section::Error when it cannot.
  StreamWriter(const std::string& path, const Stream& head);
  StreamWriter(const StreamWriter&) = delete;
  StreamWriter& operator=(const StreamWriter&) = delete;
  /// Removes the temporary file of an unfinished file output.
  ~StreamWriter();
  /// Writes one part: `# part LABEL`, then the part's issues, notes and tables (every
  /// table with its header, also when it has no rows) and flushes.
  void part(const std::string& label, const Stream& part);
  /// Writes `# end` and closes the output.
  void finish();

private:
  std::string path_;
  std::unique_ptr<detail::ByteSink> out_;
  bool finished_ = false;
};

/// Appends the rows of `from` to `to`, taking its name and columns when `to` has none
/// (to gather a table over the parts of a stream). Throws section::Error when the columns
/// differ or `from` holds a partial row.
void append_rows(Table& to, const Table& from);

/// Shortest round-trip decimal text of a double.
std::string format_number(double value);

}  // namespace section
