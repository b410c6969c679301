// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Shared plumbing of the command-line tools: common flags, the single top-level catch,
// exit codes (0 success or --help, 1 bad data, 2 bad usage, 3 some sections without a
// result).
#include "section/io/stream.h"
#include "section/pipe/run_stage.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <iosfwd>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace section::tool {

/// The tools' exit statuses (README, "Exit status").
enum ExitStatus : int {
  exit_ok = 0,          ///< success, --help, --version
  exit_bad_data = 1,    ///< bad input data (a message names the file and line or section)
  exit_bad_usage = 2,   ///< bad command line
  exit_incomplete = 3,  ///< the output is written, but some sections asked for have no result
};

/// Thrown by a tool's body once its output is complete when some sections asked for have
/// no result: run_tool prints `NAME: incomplete: message` and returns exit_incomplete.
struct Incomplete : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Thrown by a tool's body on a command line that cannot work (a stream to or from a
/// terminal): run_tool prints `NAME: usage error: message` and returns exit_bad_usage.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// True when the output `output` ("-" = standard output) is a terminal: isatty(1), or the
/// environment variable SECTION_ASSUME_TTY is "1" or "stdout" (tests force it: ctest has no
/// terminal). A named file is never one.
bool output_is_terminal(const std::string& output);

/// True when the input `input` ("-" = standard input) is a terminal: isatty(0), or
/// SECTION_ASSUME_TTY is "1" or "stdin".
bool input_is_terminal(const std::string& input);

/// Declares --allow-partial bound to `allow` (accept a result without some sections: exit 0).
void add_allow_partial(CLI::App& app, bool& allow);

/// The sections a stage was asked about and those it gave a result for, tallied over the
/// parts of its output as they are written (StageRun::written).
class SectionTally {
public:
  /// `input`: the table whose sections the stage works on; `output`: the table it writes.
  SectionTally(std::string input, std::string output)
      : input_(std::move(input)), output_(std::move(output)) {}
  /// Takes a part (or the whole stream): its frames, issues and input table's sections are
  /// asked about, its output table's sections have a result.
  void add(const section::Stream& part);
  /// Throws Incomplete (naming the sections without a result) unless every section asked
  /// about has one or `allow_partial`.
  void check(bool allow_partial) const;

private:
  std::string input_, output_;
  std::set<int> asked_, done_;
};

/// Flags every tool has.
struct Common {
  std::string input = "-";   ///< -i/--input, "-" = standard input
  std::string output = "-";  ///< -o/--output, "-" = standard output
};

/// Throws UsageError when the stream a tool writes would go to a terminal (420 KB of
/// numbers nobody reads): `the stream would go to the terminal: redirect it (> FILE) or
/// pipe it (| NEXT)`.
void refuse_terminal_output(const Common& common, const std::string& next);

/// Declares -i/--input (also as the first positional argument), -o/--output and
/// --max-memory (section::set_memory_limit).
void add_common(CLI::App& app, Common& common);

/// Bytes of a size such as "100000", "512M", "8G", "1.5GB" (k, M, G, T, P: powers of 1000);
/// 0 when it is not one.
std::size_t byte_size(const std::string& text);

/// Parses argv into the options that `declare` binds: -1 when the tool is to run, else its
/// exit code: 0 after --help or --version (written to `out`), 2 on bad usage
/// (`NAME: usage error: ...` to `err`).
int parse_args(const std::string& name, const std::string& description, int argc, char** argv,
               const std::function<void(CLI::App&)>& declare, std::ostream& out, std::ostream& err);

/// parse_args on an App of the caller's (to look at its options after).
int parse_app(CLI::App& app, const std::string& name, int argc, char** argv,
              const std::function<void(CLI::App&)>& declare, std::ostream& out, std::ostream& err);

/// Why the command line names one file twice where that would lose data: an output
/// (-o, --params, --thickness, --report, --second-view, --truth, --plot) that is an input (the input, --view,
/// --planes) or another output, by device and inode (a symlink or hard link to it counts; /dev/null and "-"
/// do not); "" when none does.
std::string same_files(CLI::App& app);

/// Why an output (-o, --params, --thickness, --report, --second-view, --truth, --plot) cannot be
/// written, checked before any work: its directory does not exist or cannot be written to;
/// "" when every one can.
std::string unwritable_outputs(CLI::App& app);

/// Installs the handlers of SIGINT, SIGTERM, SIGHUP and SIGQUIT that remove the outputs'
/// temporary files (section::remove_temporary_files) and end the tool as the signal would;
/// ignores SIGXFSZ, so that a write past `ulimit -f` fails with an error naming the file.
void remove_outputs_on_signals();

/// An error message without the tool's name repeated: "slice: x" and "FILE: slice: x" lose
/// the "slice: " that `NAME: error: ` already says.
std::string tidy_message(const std::string& name, std::string message);

/// Parses argv as parse_args does, refuses the same file given twice (same_files: exit 2),
/// installs remove_outputs_on_signals, then runs `body`. Prints `NAME: error: message` on
/// stderr and returns 1 on section::Error or any other exception, 2 on bad usage, 3
/// (`NAME: incomplete: message`) on Incomplete, 0 on success or --help/--version.
int run_tool(const std::string& name, const std::string& description, int argc, char** argv,
             const std::function<void(CLI::App&)>& declare, const std::function<void()>& body);

/// A tool's command line read into its options struct `Args` (tools/args/): Args::name,
/// Args::description and args.declare(app) bind them. Returns as parse_args does; tests call
/// it without the binary.
template <class Args>
int parse(int argc, char** argv, Args& args, std::ostream& out, std::ostream& err) {
  return parse_args(
      Args::name, Args::description, argc, argv, [&](CLI::App& app) { args.declare(app); }, out, err);
}

/// The main of a tool: argv into `Args`, then `body` under run_tool's single catch.
template <class Args>
int run(int argc, char** argv, const std::function<void(const Args&)>& body) {
  Args args;
  return run_tool(
      Args::name, Args::description, argc, argv, [&](CLI::App& app) { args.declare(app); },
      [&] { body(args); });
}

/// Calls `stage`; a section::Error it throws is rethrown with the input's name in front
/// (`blade.csv: pipe: table 'points' has no column 'v'`) unless the message already names
/// it, so that every error of a tool names the file it came from ("-" = `<stdin>`).
void with_input(const std::string& input, const std::function<void()>& stage);

/// Declares the option `flag` bound to `value`, checked by `check`, its default shown in --help.
template <class T>
CLI::Option* add_checked(CLI::App& app, const std::string& flag, T& value, const std::string& help,
                         const CLI::Validator& check) {
  return app.add_option(flag, value, help)->check(check)->capture_default_str();
}

/// Accepts a number above 0 ("must be a number above 0, got '0'"): CLI::PositiveNumber
/// answers with the range 0 to 1.8e308 written out in full.
extern const CLI::Validator positive;

/// Accepts a length unit units.h knows (mm, m, cm, um, in), naming them when refused.
extern const CLI::Validator length_unit;

/// "mm, m, cm, um, in": the units --units takes, for help texts.
std::string length_unit_names();

/// The command line as one line, for the stream's history.
std::string command_line(int argc, char** argv);

/// A stage of the pipe as section::run_stage runs it, from the common flags: input,
/// output, `history` (the command line) added to the stream's, `threads` parts at a time,
/// and `stage` run under with_input.
section::StageRun stage_run(const Common& common, const std::string& history, int threads,
                            const std::function<void(section::Stream&, int threads)>& stage);

/// stage_run for a stream stage `stage(stream, options)` (smooth_stream, fit_spline_stream,
/// camber_stream): each part staged with `options`, its threads as many as run_stage allows.
template <class Options>
section::StageRun stage_run(const Common& common, const std::string& history, const Options& options,
                            void (*stage)(section::Stream&, const Options&)) {
  return stage_run(common, history, options.threads, [&options, stage](section::Stream& part, int threads) {
    Options o = options;
    o.threads = threads;
    stage(part, o);
  });
}

/// Prints `STAGE: warning: section S[ loop L]: message` on stderr for each issue of `stream`
/// that `stage` recorded (with the loop when `loops`).
void warn_issues(const std::string& stage, const section::Stream& stream, bool loops);

/// The name of an input in messages: the path, or `<stdin>` for "-".
std::string input_name(const std::string& input);

/// True when `text` ends with `tail`.
bool ends_with(const std::string& text, const std::string& tail);

}  // namespace section::tool
