// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file pipe/run_stage.h
/// The part scheduler: runs a stage of the pipe (smooth, fitspline, camber) over a stream
/// read from a file or standard input, part by part when the stream is split into parts.
#include "section/io/stream.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace section {

/// A stage of the pipe (smooth, fitspline, camber) as run_stage runs it.
struct StageRun {
  std::string input = "-";   ///< stream to read ("-" = standard input)
  std::string output = "-";  ///< stream to write ("-" = standard output)
  std::string history;       ///< line added to the stream's history
  int threads = 0;           ///< parts staged at a time, or threads of a whole stream; 0 = all cores
  /// The stage: runs on each part (or the whole stream), from several threads at once,
  /// told how many threads it may use itself (1 for a part, `threads` for a whole stream).
  std::function<void(Stream&, int threads)> stage;
  /// Sees the preamble (units, history, notes) before any part is staged; for a stream not
  /// split into parts, the whole stream before it is staged.
  std::function<void(const Stream& head)> preamble;
  /// Sees each part (or the whole stream) as it is written, in order, from one thread.
  std::function<void(const Stream&)> written;
  /// When set, the parts (or the whole stream) are held until every one is staged, then
  /// given here together, in order, before any is written: for a last stage that needs
  /// every section (camber's check across the blade). `written` then sees them after it.
  std::function<void(const std::vector<Stream*>& parts)> hold;
  /// Runs once all is staged, before `# end`; may throw to leave the output unfinished.
  std::function<void()> before_end;
  /// Turns an input that is not a stream into one (camber: a plain profile); unset, such
  /// input is refused.
  std::function<Stream(const std::string& text, const std::string& source)> other_input;
  /// Columns of the input ({table, column}, none of them ids) whose values the stage never
  /// reads, only passes on. In the parts of a stream given in mm, where a table's rows are
  /// passed on as they came (Table::source), such cells are checked as any cell is (the
  /// same refusal of a bad one) but not decoded: NaN in Table::values.
  std::vector<std::pair<std::string, std::string>> unread;
};

/// Runs a stage of the pipe:
/// - a stream split into parts is read, staged and written part by part: up to
///   `threads` parts at a time, each written with StreamWriter as soon as it and the parts
///   before it are done, so that the tools of a pipe work side by side;
/// - any other stream is read, staged and written whole (write_stream).
/// Every part (or the whole stream) is checked against the schema (validate_stream) before
/// it is staged. Throws section::Error naming the input and its line (or table and section)
/// on malformed input (a stream split into parts must end with `# end`), and whatever the
/// callbacks throw; the output then lacks its `# end` line, or is not written. Threads that
/// cannot start (a low `ulimit -v`) are done without: with none, the parts are staged one
/// by one on the calling thread.
void run_stage(const StageRun& run);

}  // namespace section
