#pragma once
/// @file pipe.h
/// The pipe stream that `slice | smooth | fitspline | camber` pass along: named numeric
/// tables plus metadata, written as CSV with `#` lines. docs/FORMAT.md is the reference.
/// This module is the only place where the stream is parsed or formatted.
#include "section/frame.h"

#include <cstddef>
#include <iosfwd>
#include <map>
#include <memory>
#include <string_view>
#include <string>
#include <utility>
#include <vector>

namespace section {

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
  /// Set by parse_stream on large tables: format_stream writes `rows` back as they came
  /// while columns and values are still those read, so that a stage passing a table
  /// through does not format it again (the same numbers, in less time). Null for tables
  /// made in memory; a changed table is formatted from its values.
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
  std::string units = "mm";                  ///< length unit of every coordinate
  std::vector<std::string> history;          ///< one line per tool that wrote the stream
  std::vector<std::string> notes;            ///< free `# key value` lines kept as they came
  std::vector<SectionIssue> issues;          ///< per-section failures so far
  std::vector<Table> tables;                 ///< tables in stream order

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

/// Parses a plain CSV table (not a stream): `#` lines and blank lines skipped, the first
/// remaining line is the header of column names, then numeric rows with as many values,
/// separated by commas or blanks. The table is named after `source`. Throws section::Error
/// naming `source` and the line.
Table parse_csv(std::string_view text, const std::string& source);

/// Parses a plain ordered 2D profile: one point a line, x and y in the first two columns
/// (comma or blank separated; further columns ignored); leading title lines and `#` lines
/// are skipped, as in airfoil .dat files. Throws section::Error naming `source` and the line.
std::vector<Eigen::Vector2d> parse_profile(std::string_view text, const std::string& source);

/// Formats one table as a plain CSV file (header row, then the rows; no `#` lines), for
/// tools that also write a table on its own (camber --params, smooth --report).
std::string format_csv(const Table& table);

/// Section frames of a stream (table "frames"), by section id.
std::map<int, Frame> frames(const Stream& stream);

/// Adds or replaces the "frames" table from frames by section id.
void put_frames(Stream& stream, const std::map<int, Frame>& frames);

/// Reads a whole file ("-" = standard input) into memory; throws section::Error naming
/// the file when it cannot be opened or read.
std::string read_file(const std::string& path);

/// Writes `bytes` to `path` ("-" = standard output); throws section::Error on failure.
void write_file(const std::string& path, const std::string& bytes);

/// Shortest round-trip decimal text of a double.
std::string format_number(double value);

}  // namespace section
