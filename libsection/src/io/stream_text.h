// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the stream's parser, formatter, writer and part reader share (the stream's text form).
#include "section/error.h"
#include "section/io/stream.h"

#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace section::detail {

/// Throws `pipe: SOURCE:LINE: what`.
[[noreturn]] void stream_fail(const std::string& source, std::size_t line, const std::string& what);

/// A `# key rest` line: its key ("table", "part", "history", ...) and the rest, trimmed
/// (line ends dropped).
struct MetaLine {
  std::string_view key, rest, body;  ///< body: all after '#', trimmed
};
MetaLine meta_line(std::string_view line);

/// The error for a stream split into parts that lacks its `# end`.
Error truncated_parts(const std::string& source);

/// True for the columns that hold ids (integers, 0 or more): section, loop, side, index.
inline bool is_id_column(std::string_view name) {
  return name == "section" || name == "loop" || name == "side" || name == "index";
}

/// The '\n' in `s`, found by memchr (a quarter of the instructions of std::count on the
/// rows of a stream).
inline std::size_t count_lines(std::string_view s) {
  std::size_t n = 0;
  const char* const end = s.data() + s.size();
  for (const char* p = s.data(); (p = static_cast<const char*>(std::memchr(p, '\n', std::size_t(end - p))));
       ++p)
    ++n;
  return n;
}

/// `s` with its line ends made spaces, for a `#` line.
std::string one_line(std::string s);

/// A part of a stream split into parts is parsed alone: no version line, its lines numbered
/// from `first_line`.
struct PartText {
  bool is_part = false;
  std::size_t first_line = 1;
  int threads = 0;  ///< cores a large table's rows are parsed by (0: all)
};

/// parse_stream; the source rows of large tables are kept as parts of `owner` when it holds
/// `text`, else as copies.
Stream parse_stream_text(std::string_view text, const std::string& source,
                         const std::shared_ptr<const std::string>& owner, const PartText& part = {});

/// The stream's text in order: formatted pieces and the source rows of unchanged tables.
struct FormattedStream {
  std::vector<std::string> formatted;   ///< pieces made here
  std::vector<std::string_view> parts;  ///< every piece in order: views of `formatted` or of sources
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& p : parts) n += p.size();
    return n;
  }
};

/// The preamble of a stream: version, units, history, notes.
std::string format_preamble(const Stream& stream);

/// The stream's text: the preamble, then issues and tables; for a part (`part_line` not
/// empty), that line and the part's notes instead of the preamble.
FormattedStream format_parts(const Stream& stream, const std::string& part_line = "");

}  // namespace section::detail
