#include "common/tool.h"

#include "section/units.h"

#include "section/error.h"
#include "section/io/stream.h"
#include "section/pipe/run_stage.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <new>

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
}

int parse_args(const std::string& name, const std::string& description, int argc, char** argv,
               const std::function<void(CLI::App&)>& declare, std::ostream& out, std::ostream& err) {
  CLI::App app{description, name};
  app.set_version_flag("--version", std::string(name) + " (libsection) " + SECTION_VERSION);
  app.get_formatter()->column_width(34);
  try {
    declare(app);
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e, out, err);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    err << name << ": usage error: " << e.what() << "\n"
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
  const int code = parse_args(name, description, argc, argv, declare, std::cout, std::cerr);
  if (code >= 0) return code;
  try {
    body();
    return exit_ok;
  } catch (const Incomplete& e) {
    std::cerr << name << ": incomplete: " << e.what() << "\n";
    return exit_incomplete;
  } catch (const std::bad_alloc&) {
    std::cerr << name << ": error: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << name << ": error: " << e.what() << "\n";
  }
  return 1;
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
    if (loops) std::cerr << " loop " << issue.loop;
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
      // from_chars: the whole text, no locale, as the tools read their number lists.
      double v = 0;
      const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
      if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !(v > 0) || !std::isfinite(v))
        return "must be a number above 0, got '" + text + "'";
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
