// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the stream's parser, formatter, writer and part reader share (the stream's text form).
#include "section/error.h"
#include "section/io/stream.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

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

/// The '\n' in `s`: 64 bytes at a time where SSE2 is there (x86-64), in byte counters
/// summed every 63 rounds (at most 252 a lane); a memchr per line (over twice the
/// instructions) elsewhere and for the tail.
inline std::size_t count_lines(std::string_view s) {
  std::size_t n = 0;
  const char* p = s.data();
  const char* const end = p + s.size();
#ifdef __SSE2__
  const __m128i nl = _mm_set1_epi8('\n');
  const auto hits = [&](const char* at) {
    return _mm_cmpeq_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(at)), nl);  // -1 a '\n'
  };
  while (end - p >= 64) {
    const std::size_t rounds = std::min<std::size_t>(63, std::size_t(end - p) / 64);
    __m128i counts = _mm_setzero_si128();
    for (std::size_t k = 0; k < rounds; ++k, p += 64)
      counts =
          _mm_sub_epi8(_mm_sub_epi8(_mm_sub_epi8(_mm_sub_epi8(counts, hits(p)), hits(p + 16)), hits(p + 32)),
                       hits(p + 48));
    const __m128i sums = _mm_sad_epu8(counts, _mm_setzero_si128());
    n += std::size_t(_mm_cvtsi128_si32(sums)) + std::size_t(_mm_extract_epi16(sums, 4));
  }
#endif
  for (; (p = static_cast<const char*>(std::memchr(p, '\n', std::size_t(end - p)))); ++p) ++n;
  return n;
}

/// `s` with its line ends made spaces, for a `#` line.
std::string one_line(std::string s);

/// "its N values are not whole rows of its C columns" when `t`'s values end in a partial
/// row (a table built in memory), else empty.
std::string partial_rows(const Table& t);

/// A part of a stream split into parts is parsed alone: no version line, its lines numbered
/// from `first_line`.
struct PartText {
  bool is_part = false;
  std::size_t first_line = 1;
  int threads = 0;  ///< cores a large table's rows are parsed by (0: all)
  /// Columns ({table, column}, not ids) whose values the stage never reads: where a table's
  /// rows are kept as text (Table::source), their cells are checked as the parse checks
  /// any cell but not decoded, and read as NaN (StageRun::unread).
  const std::vector<std::pair<std::string, std::string>>* unread = nullptr;
};

/// parse_stream; the source rows of large tables are kept as parts of `owner` when it holds
/// `text`, else as copies.
Stream parse_stream_text(std::string_view text, const std::string& source,
                         const std::shared_ptr<const std::string>& owner, const PartText& part = {});

/// The stream's text in order: formatted pieces and the source rows of unchanged tables.
struct FormattedStream {
  std::vector<std::string> formatted;         ///< pieces made here
  std::vector<std::unique_ptr<char[]>> rows;  ///< rows formatted here (into buffers not zeroed first)
  std::vector<std::string_view> parts;  ///< every piece in order: views of `formatted`, `rows` or sources
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
