// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/stream_reader.h
/// Reading a stream part by part as it comes (docs/FORMAT.md, "Parts"): the preamble, each
/// `# part`, the closing `# end`, from a file or standard input.
#include "section/io/stream.h"

#include <cstddef>
#include <memory>
#include <set>
#include <string>
#include <string_view>

namespace section {

namespace detail {
class ByteSource;
}

/// One part of a stream split into parts, as read.
struct StreamPart {
  std::string label;                        ///< what follows `# part`
  std::shared_ptr<const std::string> text;  ///< its lines, from its `# part` line on
  std::size_t first_line = 0;               ///< the number of its `# part` line in the input
};

/// Parses one part read by PartReader; its tables keep their rows in `part.text`
/// (Table::source). Large tables are parsed by `threads` cores (0: all; 1 where parts are
/// parsed side by side). Throws section::Error naming `source` and the line.
Stream parse_stream_part(const StreamPart& part, const std::string& source, int threads = 0);

/// Reads a stream from a file or standard input, part by part when it is split into parts.
class PartReader {
public:
  /// Opens `path` ("-" = standard input) and reads up to the first `# part`, `# table` or
  /// data line. Throws section::Error when it cannot be opened or read, holds binary data,
  /// UTF-16 or CR-only line ends; later reads throw for a line longer than max_text_line and
  /// for a part (or a stream not split into parts) larger than max_input_bytes() (io/limits.h).
  explicit PartReader(const std::string& path);
  ~PartReader();
  PartReader(const PartReader&) = delete;
  PartReader& operator=(const PartReader&) = delete;

  /// The input in messages: the path, or "<stdin>".
  const std::string& source() const { return source_; }
  /// True when the stream is split into parts.
  bool parted() const { return parted_; }
  /// The preamble of a stream split into parts (version, units, history, notes), parsed.
  /// Throws section::Error when it is malformed or holds issues.
  Stream preamble() const;
  /// The whole text of a stream that is not split into parts (the rest of the input read).
  std::string whole();
  /// The next part, read up to the next `# part` or `# end`; false once `# end` is passed
  /// and the rest of the input is found blank. Throws section::Error naming the line for
  /// anything after `# end`, a second part of one section, and when the input ends before
  /// `# end` (a truncated stream).
  bool next(StreamPart& part);

private:
  // The next line (counted); throws for one longer than max_text_line.
  bool next_line(std::string_view& line);
  // Appends the whole lines at hand up to the next '#' line to text_ in one piece (a part's
  // rows; next_line takes the '#' lines and a line not all at hand).
  void take_rows();
  // Throws when `text` (WHAT of the input) is larger than max_input_bytes().
  void held(const std::string& text, const std::string& what) const;

  std::unique_ptr<detail::ByteSource> in_;
  std::string source_, head_, text_, label_;
  std::size_t line_no_ = 0, first_line_ = 0;
  bool parted_ = false, ended_ = false;
  std::size_t end_error_line_ = 0;  // a `# end` line with words after it, reported after the last part
  std::set<std::string> labels_;    // of the parts so far
};

}  // namespace section
