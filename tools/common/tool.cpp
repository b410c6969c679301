// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/tool.h"

#include "section/units.h"

#include "section/error.h"
#include "section/io/limits.h"
#include "section/io/stream.h"
#include "section/pipe/run_stage.h"

#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <new>
#include <optional>
#include <utility>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#if __has_include(<malloc.h>)
#include <malloc.h>  // mallopt (glibc)
#endif

namespace section::tool {

namespace {
std::string basename_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}
}  // namespace

void add_common(CLI::App& app, Common& common) {
  app.add_option("input,-i,--input", common.input, "Input file, - for standard input")->capture_default_str();
  app.add_option("-o,--output", common.output, "Output file, - for standard output")->capture_default_str();
  app.add_option_function<std::string>(
         "--max-memory", [](const std::string& size) { set_memory_limit(byte_size(size)); },
         "Memory the inputs may take (e.g. 8G): a stream, a part or a mesh up to a quarter of it, a "
         "cloud from a pipe up to all of it (a temporary copy), the slab points of all planes up to half; "
         "default: the memory available (RAM, ulimit -v, cgroup)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return byte_size(text) > 0 ? std::string()
                                       : "must be a size such as 4G, 512M or 100000000, got '" + text + "'";
          },
          "SIZE"));
}

std::size_t byte_size(const std::string& text) {
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || !(v > 0) || !std::isfinite(v)) return 0;
  std::string unit(r.ptr, text.data() + text.size());
  if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();
  const std::string units = "kmgtp";
  double scale = 1;
  if (unit.size() == 1) {
    const auto k = units.find(static_cast<char>(std::tolower(static_cast<unsigned char>(unit[0]))));
    if (k == std::string::npos) return 0;
    scale = std::pow(1000.0, double(k + 1));
  } else if (!unit.empty()) {
    return 0;
  }
  return v * scale < 1.8e19 ? static_cast<std::size_t>(v * scale) : 0;
}

namespace {

// `text` read whole as a number (from_chars: no locale, as the tools read their number
// lists; "inf" and "nan" too), or nothing.
std::optional<double> whole_number(const std::string& text) {
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size()) return std::nullopt;
  return v;
}

// The refusal of a non-finite value, whichever check finds it.
std::string not_finite(const std::string& text) {
  return "must be a finite number, got '" + text + "'";
}

// CLI11's "Value -1 not in range 0.000000 to 1797693...(309 digits).000000" (its
// NonNegativeNumber) as "Value -1 is below 0"; "Value inf ..." as a non-finite number.
std::string readable_range(std::string what) {
  const std::string range = " not in range ", top = " to 179769313486231570", value = "Value ";
  const auto at = what.find(range), to = what.find(top);
  if (at == std::string::npos || to == std::string::npos || to < at) return what;
  const auto v0 = what.rfind(value, at);
  if (v0 != std::string::npos) {
    const std::string text = what.substr(v0 + value.size(), at - v0 - value.size());
    if (const auto v = whole_number(text); v && !std::isfinite(*v))
      return what.substr(0, v0) + not_finite(text);
  }
  std::string low = what.substr(at + range.size(), to - at - range.size());
  while (low.find('.') != std::string::npos && (low.back() == '0' || low.back() == '.')) low.pop_back();
  const auto end = what.find_first_not_of("0123456789.", to + top.size());
  return what.substr(0, at) + " is below " + low + (end == std::string::npos ? "" : what.substr(end));
}

// A non-finite value given to a numeric option ("--slab nan", "--at 1,inf"): CLI11's
// number checks let NaN through.
void refuse_non_finite(CLI::App& app) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_type_name().find("FLOAT") == std::string::npos) continue;
    for (const std::string& text : o->results()) {
      if (const auto v = whole_number(text); v && !std::isfinite(*v))
        throw CLI::ValidationError(o->get_name(), not_finite(text));
    }
  }
}

// An option given an empty value ("--tolerances ''", "--at ''"): an unset shell variable,
// which would otherwise read as the option left out, or as 0.
void refuse_empty(CLI::App& app) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_type_size_min() <= 0) continue;  // a flag
    for (const std::string& text : o->results())
      if (text.find_first_not_of(" \t") == std::string::npos)
        throw CLI::ValidationError(o->get_name(), "an empty value (is a shell variable unset?)");
  }
}

}  // namespace

int parse_args(const std::string& name, const std::string& description, int argc, char** argv,
               const std::function<void(CLI::App&)>& declare, std::ostream& out, std::ostream& err) {
  CLI::App app{description, name};
  return parse_app(app, name, argc, argv, declare, out, err);
}

int parse_app(CLI::App& app, const std::string& name, int argc, char** argv,
              const std::function<void(CLI::App&)>& declare, std::ostream& out, std::ostream& err) {
  app.set_version_flag("--version", std::string(name) + " (libsection) " + SECTION_VERSION);
  app.get_formatter()->column_width(34);
  try {
    declare(app);
    app.parse(argc, argv);
    refuse_empty(app);
    refuse_non_finite(app);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    err << name << ": usage error: " << readable_range(e.what()) << "\n"
        << "Run '" << name << " --help' for the options.\n";
    return 2;
  }
  return -1;
}

int run_tool(const std::string& name, const std::string& description, int argc, char** argv,
             const std::function<void(CLI::App&)>& declare, const std::function<void()>& body) {
#ifdef M_MMAP_THRESHOLD
  // Large buffers from the heap and kept there once freed: a stage allocates and frees
  // its sections' arrays over and over, and fresh pages from the kernel (zeroed, faulted
  // in one by one) cost the pipe about a tenth of its time (glibc; the defaults elsewhere).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  mallopt(M_TOP_PAD, 64 << 20);
#endif
  CLI::App app{description, name};
  const int code = parse_app(app, name, argc, argv, declare, std::cout, std::cerr);
  if (code >= 0) return code;
  const std::string clash = same_files(app);
  if (!clash.empty()) {
    std::cerr << name << ": usage error: " << clash << "\n";
    return 2;
  }
  // Before the work: a report that cannot be written once the stream has been.
  if (const std::string unwritable = unwritable_outputs(app); !unwritable.empty()) {
    std::cerr << name << ": error: " << unwritable << "\n";
    return exit_bad_data;
  }
  const CLI::Option* input = app.get_option_no_throw("--input");
  if (input && (input->count() == 0 || input->as<std::string>() == "-") && input_is_terminal("-")) {
    // Waiting on a terminal's keyboard without a word looks like a hang.
    std::cerr << name << ": usage error: no input: give a file (" << name << " FILE) or pipe one in (... | "
              << name << ")\n";
    return exit_bad_usage;
  }
  remove_outputs_on_signals();
  try {
    body();
    return exit_ok;
  } catch (const UsageError& e) {
    std::cerr << name << ": usage error: " << e.what() << "\n";
    return exit_bad_usage;
  } catch (const Incomplete& e) {
    std::cerr << name << ": incomplete: " << e.what() << "\n";
    return exit_incomplete;
  } catch (const std::bad_alloc&) {
    std::cerr << name << ": error: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << name << ": error: " << tidy_message(name, e.what()) << "\n";
  }
  return 1;
}

namespace {
// SECTION_ASSUME_TTY names the standard stream (`stream`: "stdout" or "stdin") taken as a
// terminal, or "1" for both.
bool assumed_terminal(const char* stream) {
  const char* v = std::getenv("SECTION_ASSUME_TTY");
  return v && (std::string(v) == "1" || std::string(v) == stream);
}
}  // namespace

bool output_is_terminal(const std::string& output) {
  return output == "-" && (::isatty(STDOUT_FILENO) || assumed_terminal("stdout"));
}

bool input_is_terminal(const std::string& input) {
  return input == "-" && (::isatty(STDIN_FILENO) || assumed_terminal("stdin"));
}

void refuse_terminal_output(const Common& common, const std::string& next) {
  if (output_is_terminal(common.output))
    throw UsageError("the stream would go to the terminal: redirect it (> FILE) or pipe it (| " + next + ")");
}

void add_allow_partial(CLI::App& app, bool& allow) {
  app.add_flag("--allow-partial", allow,
               "Exit 0 even when some sections have no result (each has an issue); without it such a run "
               "exits 3 once its output is written");
}

void SectionTally::add(const section::Stream& part) {
  auto sections_of = [](const section::Table* t, std::set<int>& into) {
    if (!t) return;
    const long c = t->find_column("section");
    if (c < 0) return;
    for (std::size_t r = 0; r < t->rows(); ++r) into.insert(static_cast<int>(t->at(r, std::size_t(c))));
  };
  sections_of(part.find("frames"), asked_);
  sections_of(part.find(input_), asked_);
  sections_of(part.find(output_), done_);
  for (const auto& issue : part.issues)
    if (issue.section >= 0) asked_.insert(issue.section);
}

void SectionTally::check(bool allow_partial) const {
  std::vector<int> missing;
  for (int s : asked_)
    if (!done_.count(s)) missing.push_back(s);
  if (missing.empty() || allow_partial) return;
  std::string list;
  for (std::size_t i = 0; i < missing.size() && i < 20; ++i)
    list += (i ? ", " : "") + std::to_string(missing[i]);
  if (missing.size() > 20) list += ", ...";
  throw Incomplete(std::to_string(missing.size()) + " of " + std::to_string(asked_.size()) +
                   " sections have no " + output_ + " (section" + (missing.size() > 1 ? "s " : " ") + list +
                   ": see their issues); the output holds the others; --allow-partial accepts this");
}

namespace {

// A file's identity: its device and inode when it exists, else its directory's and its name.
struct FileId {
  dev_t dev = 0;
  ino_t ino = 0;
  std::string name;  // for a file not there yet
  bool operator==(const FileId& o) const { return dev == o.dev && ino == o.ino && name == o.name; }
};

// The directory `path` names a file in: "." for a bare name, "/" at the root.
std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

// The identity of `path`; false for "-", a file that cannot be checked, or one that is not
// a regular file (/dev/null may be given for several outputs).
bool file_id(const std::string& path, FileId& id) {
  if (path.empty() || path == "-") return false;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id = {st.st_dev, st.st_ino, ""};
    return S_ISREG(st.st_mode);
  }
  const auto slash = path.find_last_of('/');
  if (::stat(directory_of(path).c_str(), &st) != 0) return false;
  id = {st.st_dev, st.st_ino, path.substr(slash == std::string::npos ? 0 : slash + 1)};
  return true;
}

// The flags that name output files, for every tool: a new one is added here.
const std::initializer_list<const char*> output_flags = {
    "--output", "--params", "--thickness", "--report", "--second-view", "--truth", "--plot"};

// Every path given to the options named in `flags`, with the flag.
std::vector<std::pair<std::string, std::string>> paths_of(CLI::App& app,
                                                          std::initializer_list<const char*> flags) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const char* flag : flags)
    if (const CLI::Option* o = app.get_option_no_throw(flag))
      for (const std::string& path : o->results()) out.emplace_back(flag, path);
  return out;
}

extern "C" void remove_and_reraise(int sig) {
  section::remove_temporary_files();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

std::string same_files(CLI::App& app) {
  // The flags that name input files, for every tool: a new one is added here.
  const auto inputs = paths_of(app, {"--input", "--view", "--planes"});
  const auto outputs = paths_of(app, output_flags);
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    FileId out;
    if (!file_id(outputs[k].second, out)) continue;
    for (const auto& [flag, path] : inputs) {
      FileId in;
      if (file_id(path, in) && in == out)
        return outputs[k].first + " " + outputs[k].second + " is the input " + path + " (" + flag +
               "): it would be overwritten";
    }
    for (std::size_t j = 0; j < k; ++j) {
      FileId other;
      if (file_id(outputs[j].second, other) && other == out)
        return outputs[k].first + " " + outputs[k].second + " is the output of " + outputs[j].first +
               " too: give each output its own file";
    }
  }
  return "";
}

std::string unwritable_outputs(CLI::App& app) {
  for (const auto& [flag, path] : paths_of(app, output_flags)) {
    if (path.empty() || path == "-") continue;
    const std::string dir = directory_of(path);
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
      return flag + " " + path + ": the directory " + dir + " does not exist";
    if (::access(dir.c_str(), W_OK) != 0 && ::access(path.c_str(), W_OK) != 0)
      return flag + " " + path + ": " + dir + " cannot be written to";
  }
  return "";
}

void remove_outputs_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_and_reraise;
  sigemptyset(&action.sa_mask);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
    struct sigaction old {};
    // A signal ignored by the caller (nohup) stays ignored.
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler != SIG_IGN) ::sigaction(sig, &action, nullptr);
  }
  // Past `ulimit -f` a write fails with EFBIG (an error naming the file) instead of killing
  // the tool with its temporary file left behind.
  std::signal(SIGXFSZ, SIG_IGN);
}

std::string tidy_message(const std::string& name, std::string message) {
  // "slice: the slab ..." or "FILE: slice: the slab ..." after "slice: error: ".
  const std::string own = name + ": ";
  if (message.rfind(own, 0) == 0) return message.substr(own.size());
  const auto colon = message.find(": ");
  if (colon != std::string::npos && message.compare(colon + 2, own.size(), own) == 0)
    message.erase(colon + 2, own.size());
  return message;
}

void with_input(const std::string& input, const std::function<void()>& stage) {
  try {
    stage();
  } catch (const section::Error& e) {
    const std::string name = input_name(input);
    const std::string what = e.what();
    if (what.find(name) != std::string::npos) throw;
    throw section::Error(name + ": " + what);
  }
}

std::string command_line(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    if (i) line += ' ';
    std::string arg = i == 0 ? basename_of(argv[0]) : std::string(argv[i]);
    line += arg;
  }
  return line;
}

section::StageRun stage_run(const Common& common, const std::string& history, int threads,
                            const std::function<void(section::Stream&, int threads)>& stage) {
  section::StageRun run;
  run.input = common.input;
  run.output = common.output;
  run.history = history;
  run.threads = threads;
  run.stage = [stage, input = common.input](section::Stream& part, int part_threads) {
    with_input(input, [&] { stage(part, part_threads); });
  };
  return run;
}

void warn_issues(const std::string& stage, const section::Stream& stream, bool loops) {
  for (const auto& issue : stream.issues) {
    if (issue.stage != stage) continue;
    std::cerr << stage << ": warning: section " << issue.section;
    if (loops && issue.loop >= 0) std::cerr << " loop " << issue.loop;
    std::cerr << ": " << issue.message << "\n";
  }
}

std::string input_name(const std::string& input) {
  return input == "-" ? "<stdin>" : input;
}

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

const CLI::Validator positive(
    [](std::string& text) -> std::string {
      const auto v = whole_number(text);
      if (!v || !(*v > 0) || !std::isfinite(*v)) return "must be a number above 0, got '" + text + "'";
      return {};
    },
    "POSITIVE", "positive");

const CLI::Validator length_unit(
    [](const std::string& unit) {
      try {
        section::mm_per_unit(unit);
      } catch (const section::Error& e) {
        return std::string(e.what());
      }
      return std::string();
    },
    "UNIT", "length unit");

std::string length_unit_names() {
  std::string names;
  for (const auto& u : section::length_units()) names += std::string(names.empty() ? "" : ", ") + u.name;
  return names;
}

}  // namespace section::tool
