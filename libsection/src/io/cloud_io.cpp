#include "section/io/cloud_io.h"

#include "section/error.h"
#include "detail/parallel.h"
#include "detail/text.h"
#include "detail/ply.h"

#include <flann/flann.hpp>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <thread>

namespace section {

namespace {

using detail::is_space;
using detail::parse_double;
using detail::trim;

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower(path.substr(dot + 1));
}

// A source of bytes: a file, standard input or a pipe (read in blocks into one reused
// buffer: faster than mapping windows of the file, and a file truncated while it is read
// is a short read, not a SIGBUS), or bytes in memory.
// bytes() are the unconsumed bytes at hand; fetch() brings more after them.
class Source {
public:
  explicit Source(const std::string& path) : name_(path == "-" ? "<stdin>" : path) {
    if (path == "-") {
      file_ = stdin;
      return;
    }
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw Error("read_cloud: " + path + ": cannot open: " + std::strerror(errno));
    owned_ = true;
    struct stat st {};
    if (::fstat(fileno(file_), &st) == 0 && S_ISDIR(st.st_mode)) {
      std::fclose(file_);
      file_ = nullptr;
      throw Error("read_cloud: " + path + ": is a directory");
    }
    if (S_ISREG(st.st_mode) && st.st_size > 0)  // (files of /proc claim 0 bytes: size unknown)
      size_ = static_cast<long long>(st.st_size);
  }
  // A source over bytes in memory.
  Source(std::string_view bytes, const std::string& name) : name_(name) {
    size_ = static_cast<long long>(bytes.size());
    base_ = bytes.data();
    end_ = bytes.size();
  }
  ~Source() {
    if (owned_ && file_) std::fclose(file_);
  }
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;

  std::string_view bytes() const { return {base_ + start_, end_ - start_}; }
  void consume(std::size_t n) {
    start_ += n;
    consumed_ += n;
  }
  /// The descriptor of a regular file of known size (which pread can read anywhere), or -1.
  int regular_fd() const { return owned_ && file_ && size_ > 0 ? fileno(file_) : -1; }
  /// Bytes consumed since the start of the source: the file offset of bytes() when it is
  /// a file.
  unsigned long long offset() const { return consumed_; }

  // Makes up to n more bytes available after bytes(); returns how many (0 at the end).
  std::size_t fetch(std::size_t n) {
    if (!file_) return 0;  // in memory: all of it is at hand
    // Keep the unconsumed bytes at the front of the buffer, then read after them.
    const std::size_t keep = end_ - start_;
    if (keep + n > cap_) {
      cap_ = std::max(keep + n, 2 * cap_);
      std::unique_ptr<char[]> bigger(new char[cap_]);
      if (keep) std::memcpy(bigger.get(), base_ + start_, keep);
      buf_ = std::move(bigger);
    } else if (keep && start_) {
      std::memmove(buf_.get(), base_ + start_, keep);
    }
    base_ = buf_.get();
    start_ = 0;
    end_ = keep;
    const std::size_t got = std::fread(buf_.get() + end_, 1, n, file_);
    end_ += got;
    if (got == 0 && std::ferror(file_)) throw Error("read_cloud: " + name_ + ": read error");
    return got;
  }
  const std::string& name() const { return name_; }
  long long size() const { return size_; }  // -1 when unknown (a pipe)

private:
  std::string name_;
  std::FILE* file_ = nullptr;
  bool owned_ = false;
  long long size_ = -1;
  std::unique_ptr<char[]> buf_;
  std::size_t cap_ = 0;
  const char* base_ = nullptr;     // bytes() = base_[start_, end_)
  std::size_t start_ = 0, end_ = 0;
  unsigned long long consumed_ = 0;
};

// Collects points and hands them on in chunks.
class Chunker {
public:
  Chunker(const PointChunkFn& fn, std::size_t chunk) : fn_(fn), chunk_(std::max<std::size_t>(chunk, 1)) {
    buf_.reserve(chunk_);
  }
  void add(double x, double y, double z) {
    buf_.emplace_back(x, y, z);
    if (buf_.size() == chunk_) flush();
  }
  // Adds points in bulk; whole chunks go to the callback straight from `p`.
  void add_many(const Eigen::Vector3d* p, std::size_t n) {
    while (n > 0) {
      if (buf_.empty() && n >= chunk_) {
        fn_(p, chunk_);
        total_ += chunk_;
        p += chunk_;
        n -= chunk_;
        continue;
      }
      const std::size_t m = std::min(n, chunk_ - buf_.size());
      buf_.insert(buf_.end(), p, p + m);
      p += m;
      n -= m;
      if (buf_.size() == chunk_) flush();
    }
  }
  // Room for up to `n` points at the end of the chunk (n is cut to what fits); fill them,
  // then call commit().
  Eigen::Vector3d* room(std::size_t& n) {
    const std::size_t old = buf_.size();
    n = std::min(n, chunk_ - old);
    buf_.resize(old + n);
    return buf_.data() + old;
  }
  void commit() {
    if (buf_.size() == chunk_) flush();
  }
  void flush() {
    if (!buf_.empty()) fn_(buf_.data(), buf_.size());
    total_ += buf_.size();
    buf_.clear();
  }
  std::size_t total() const { return total_ + buf_.size(); }

private:
  const PointChunkFn& fn_;
  std::size_t chunk_;
  std::vector<Eigen::Vector3d> buf_;
  std::size_t total_ = 0;
};

[[noreturn]] void fail_line(const std::string& name, std::size_t line, const std::string& what) {
  throw Error("read_cloud: " + name + ":" + std::to_string(line) + ": " + what);
}

constexpr std::size_t block_size = 1 << 24;
constexpr std::size_t max_line = 1 << 16;

// ---------------------------------------------------------------- text (XYZ and CSV)

struct TextState {
  bool csv_header_seen = false;
  int cx = 0, cy = 1, cz = 2;  // columns of x, y, z
  int needed = 3;              // columns a row must have at least
  bool require_header = false;
};

// Splits a line into fields: commas separate, runs of blanks separate; returns the count.
int split_fields(std::string_view line, std::string_view* fields, int max_fields) {
  int n = 0;
  std::size_t i = 0;
  const std::size_t len = line.size();
  while (i < len && n < max_fields) {
    while (i < len && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < len && line[i] != ',' && line[i] != ' ' && line[i] != '\t') ++i;
    std::size_t end = i;
    while (i < len && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i < len && line[i] == ',') {
      ++i;
      fields[n++] = line.substr(start, end - start);
      if (i == len && n < max_fields) fields[n++] = std::string_view{};  // trailing comma: empty last field
      continue;
    }
    if (end > start) fields[n++] = line.substr(start, end - start);
  }
  return n;
}

std::string unquote(std::string_view s) {
  s = trim(s);
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) s = s.substr(1, s.size() - 2);
  return lower(std::string(s));
}

bool try_header(std::string_view line, TextState& st) {
  std::string_view f[64];
  const int n = split_fields(line, f, 64);
  int cx = -1, cy = -1, cz = -1;
  for (int i = 0; i < n; ++i) {
    const std::string name = unquote(f[i]);
    if (name == "x" || name == "//x") cx = i;
    if (name == "y") cy = i;
    if (name == "z") cz = i;
  }
  if (cx < 0 || cy < 0 || cz < 0) return false;
  st.cx = cx;
  st.cy = cy;
  st.cz = cz;
  st.needed = std::max({cx, cy, cz}) + 1;
  st.csv_header_seen = true;
  return true;
}

template <class Out>
void parse_text_line(std::string_view line, std::size_t line_no, TextState& st, const std::string& name,
                     Out& out, bool& first_data) {
  line = trim(line);
  if (line.empty() || line[0] == '#' || (line.size() > 1 && line[0] == '/' && line[1] == '/')) return;
  if (first_data) {
    first_data = false;
    double tmp;
    std::string_view f[64];
    const int n = split_fields(line, f, 64);
    if (n == 0 || !parse_double(trim(f[0]), tmp) || st.require_header) {
      if (try_header(line, st)) return;
      if (st.require_header)
        fail_line(name, line_no, "a CSV cloud needs a header row naming the x, y and z columns");
      if (n > 0 && !parse_double(trim(f[0]), tmp))
        fail_line(name, line_no, "expected a number in column 1, found '" + std::string(trim(f[0]).substr(0, 40)) +
                                     "' (a header row must name x, y and z columns)");
    }
  }
  std::string_view f[64];
  const int n = split_fields(line, f, std::min(64, st.needed));
  if (n < st.needed)
    fail_line(name, line_no, "expected at least " + std::to_string(st.needed) + " columns, found " + std::to_string(n));
  double v[3];
  const int cols[3] = {st.cx, st.cy, st.cz};
  for (int k = 0; k < 3; ++k) {
    const std::string_view cell = trim(f[cols[k]]);
    if (!parse_double(cell, v[k]))
      fail_line(name, line_no, "expected a number in column " + std::to_string(cols[k] + 1) + ", found '" +
                                   std::string(cell.substr(0, 40)) + "'");
    if (!std::isfinite(v[k]))
      fail_line(name, line_no, "non-finite coordinate '" + std::string(cell) + "' in column " + std::to_string(cols[k] + 1));
  }
  out.add(v[0], v[1], v[2]);
}

// The common row "x y z [more columns]" (blank or comma separated) parsed without
// splitting it into fields. True only when parse_text_line would read the same three
// values; anything unusual (comment, header, bad cell, non-finite value, a '\r' inside the
// row) returns false and the line goes to parse_text_line, which also words the error.
inline bool parse_xyz_fast(const char* p, const char* e, double* v) {
  for (int k = 0; k < 3; ++k) {
    while (p < e && (*p == ' ' || *p == '\t')) ++p;
    if (k > 0 && p < e && *p == ',') {
      ++p;
      while (p < e && (*p == ' ' || *p == '\t')) ++p;
    }
    if (p < e && *p == '+') ++p;
    const auto r = std::from_chars(p, e, v[k]);
    if (r.ec != std::errc() || !std::isfinite(v[k])) return false;
    p = r.ptr;
    // The cell must end here: at a separator, or (the last one) at the end of the line.
    if (p == e) return k == 2;
    if (*p == ' ' || *p == '\t' || *p == ',') continue;
    return k == 2 && *p == '\r' && p + 1 == e;
  }
  return true;
}

// Parses the complete lines buf[begin, end) (end just after a '\n') past the first data
// line; `line_no` counts the lines. Throws at the first bad line.
template <class Out>
void parse_text_lines(std::string_view buf, std::size_t begin, std::size_t end, std::size_t& line_no,
                      TextState& st, const std::string& name, Out& out) {
  const bool plain = st.cx == 0 && st.cy == 1 && st.cz == 2;
  const char* p = buf.data() + begin;
  const char* const stop = buf.data() + end;
  bool first_data = false;
  while (p < stop) {
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', std::size_t(stop - p)));
    ++line_no;
    if (std::size_t(nl - p) > max_line) fail_line(name, line_no, "line longer than " + std::to_string(max_line) + " characters");
    double v[3];
    if (plain && parse_xyz_fast(p, nl, v))
      out.add(v[0], v[1], v[2]);
    else
      parse_text_line(std::string_view(p, std::size_t(nl - p)), line_no, st, name, out, first_data);
    p = nl + 1;
  }
}

// Points of one piece of a text block, parsed by one worker.
struct PieceOut {
  std::vector<Eigen::Vector3d> points;
  std::size_t lines = 0;  // lines of the piece (all of them unless it failed)
  bool failed = false;    // a line is malformed: the piece is parsed again, in order, for the message
  void add(double x, double y, double z) { points.emplace_back(x, y, z); }
};

// Parses the complete lines buf[begin, end) (end just after a '\n'; the first data line
// already seen, so the state is read-only) split at line boundaries across threads.
// Points reach `out` in file order and the error thrown is that of the first bad line, as
// if parsed line by line: `line_no` is the number of lines before `begin`.
// `parts` is kept from block to block so that its buffers are reused, not faulted in anew.
void parse_text_block(std::string_view buf, std::size_t begin, std::size_t end, std::size_t& line_no,
                      const TextState& st, const std::string& name, const CloudReadOptions& opt, Chunker& out,
                      std::vector<PieceOut>& parts) {
  const std::size_t bytes = end - begin;
  std::size_t pieces = opt.threads > 0 ? std::size_t(opt.threads) : std::max(1u, std::thread::hardware_concurrency());
  pieces = std::max<std::size_t>(1, std::min(pieces * 4, bytes / (1 << 18)));  // >= 256 KiB each
  std::vector<std::size_t> cut{begin};
  for (std::size_t k = 1; k < pieces; ++k) {
    std::size_t at = begin + bytes * k / pieces;
    if (at <= cut.back()) continue;
    const std::size_t nl = buf.find('\n', at - 1);
    if (nl == std::string_view::npos || nl + 1 >= end) break;
    if (nl + 1 > cut.back()) cut.push_back(nl + 1);
  }
  cut.push_back(end);
  const std::size_t n = cut.size() - 1;
  // Each piece counts its own lines; line numbers are only needed for a message, so a
  // failed piece is parsed again once the lines before it are known.
  if (parts.size() < n) parts.resize(n);
  detail::parallel_for(n, opt.threads, [&](std::size_t k) {
    PieceOut& part = parts[k];
    part.points.clear();
    part.lines = 0;
    part.failed = false;
    part.points.reserve((cut[k + 1] - cut[k]) / 24);
    TextState local = st;
    try {
      parse_text_lines(buf, cut[k], cut[k + 1], part.lines, local, name, part);
    } catch (...) {
      part.failed = true;
    }
  });
  for (std::size_t k = 0; k < n; ++k) {
    if (parts[k].failed) {
      PieceOut again;
      TextState local = st;
      parse_text_lines(buf, cut[k], cut[k + 1], line_no, local, name, again);  // throws
    }
    if (out.total() + parts[k].points.size() > opt.max_points)
      throw Error("read_cloud: " + name + ": more than " + std::to_string(opt.max_points) + " points");
    out.add_many(parts[k].points.data(), parts[k].points.size());
    line_no += parts[k].lines;
  }
}

std::size_t read_text(Source& src, bool csv, const CloudReadOptions& opt, const PointChunkFn& fn) {
  Chunker out(fn, opt.chunk_points);
  TextState st;
  st.require_header = csv;
  bool first_data = true;
  std::size_t line_no = 0;
  std::vector<PieceOut> parts;
  // Parses the complete lines of `b`; returns the bytes used.
  const auto parse = [&](std::string_view b) {
    std::size_t used = 0, nl;
    // Line by line up to the first data line (it decides the header), then in parallel.
    while (first_data && (nl = b.find('\n', used)) != std::string_view::npos) {
      ++line_no;
      if (nl - used > max_line) fail_line(src.name(), line_no, "line longer than " + std::to_string(max_line) + " characters");
      parse_text_line(b.substr(used, nl - used), line_no, st, src.name(), out, first_data);
      if (out.total() > opt.max_points)
        throw Error("read_cloud: " + src.name() + ": more than " + std::to_string(opt.max_points) + " points");
      used = nl + 1;
    }
    if (!first_data) {
      const std::size_t last = b.rfind('\n');
      if (last != std::string_view::npos && last >= used) {
        parse_text_block(b, used, last + 1, line_no, st, src.name(), opt, out, parts);
        used = last + 1;
      }
    }
    return used;
  };
  while (true) {
    src.consume(parse(src.bytes()));
    if (src.bytes().size() > max_line)
      fail_line(src.name(), line_no + 1, "line longer than " + std::to_string(max_line) + " characters");
    if (src.fetch(block_size) == 0) break;
  }
  if (!src.bytes().empty()) {
    // The last line has no '\n': parse a copy that has one.
    std::string last(src.bytes());
    last.push_back('\n');
    parse(last);
  }
  out.flush();
  if (out.total() == 0) throw Error("read_cloud: " + src.name() + ": no points");
  return out.total();
}

// ---------------------------------------------------------------- PLY

enum class PlyFormat { ascii, binary_le, binary_be };

struct PlyProperty {
  std::string name;
  int size = 0;         // bytes of a scalar
  char kind = 'f';      // 'f' float, 'i' signed, 'u' unsigned
  bool list = false;
};

struct PlyElement {
  std::string name;
  unsigned long long count = 0;
  std::vector<PlyProperty> props;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t header_bytes = 0;
  std::size_t header_lines = 0;
};

using detail::ply_type;

// Parses the header from the start of `buf`, reading more from `src` as needed.
PlyHeader parse_ply_header(Source& src) {
  PlyHeader h;
  std::string_view buf = src.bytes();
  std::size_t pos = 0;
  bool format_seen = false;
  while (true) {
    std::size_t nl = buf.find('\n', pos);
    while (nl == std::string::npos) {
      if (buf.size() > (1 << 20)) throw Error("read_cloud: " + src.name() + ": PLY header longer than 1 MiB");
      if (src.fetch(1 << 16) == 0) throw Error("read_cloud: " + src.name() + ": truncated PLY header (no end_header)");
      buf = src.bytes();
      nl = buf.find('\n', pos);
    }
    ++h.header_lines;
    std::string_view line = trim(buf.substr(pos, nl - pos));
    pos = nl + 1;
    const std::string where = src.name() + ":" + std::to_string(h.header_lines) + ": ";
    if (h.header_lines == 1) {
      if (line != "ply") throw Error("read_cloud: " + where + "not a PLY file (no 'ply' magic)");
      continue;
    }
    std::string_view tok[8];
    int n = 0;
    {
      std::size_t i = 0;
      while (i < line.size() && n < 8) {
        while (i < line.size() && is_space(line[i])) ++i;
        const std::size_t s = i;
        while (i < line.size() && !is_space(line[i])) ++i;
        if (i > s) tok[n++] = line.substr(s, i - s);
      }
    }
    if (n == 0) continue;
    if (tok[0] == "end_header") break;
    if (tok[0] == "comment" || tok[0] == "obj_info") continue;
    if (tok[0] == "format") {
      if (n < 2) throw Error("read_cloud: " + where + "bad format line");
      if (tok[1] == "ascii") h.format = PlyFormat::ascii;
      else if (tok[1] == "binary_little_endian") h.format = PlyFormat::binary_le;
      else if (tok[1] == "binary_big_endian") h.format = PlyFormat::binary_be;
      else throw Error("read_cloud: " + where + "unknown PLY format '" + std::string(tok[1]) + "'");
      format_seen = true;
    } else if (tok[0] == "element") {
      if (n < 3) throw Error("read_cloud: " + where + "bad element line");
      PlyElement e;
      e.name = std::string(tok[1]);
      const auto r = std::from_chars(tok[2].data(), tok[2].data() + tok[2].size(), e.count);
      if (r.ec != std::errc() || r.ptr != tok[2].data() + tok[2].size())
        throw Error("read_cloud: " + where + "bad element count '" + std::string(tok[2]) + "'");
      h.elements.push_back(e);
    } else if (tok[0] == "property") {
      if (h.elements.empty()) throw Error("read_cloud: " + where + "property before any element");
      PlyProperty p;
      if (n >= 5 && tok[1] == "list") {
        p.list = true;
        p.name = std::string(tok[4]);
        char k;
        int s;
        if (!ply_type(std::string(tok[2]), s, k) || !ply_type(std::string(tok[3]), p.size, p.kind))
          throw Error("read_cloud: " + where + "unknown property type");
        p.size = s * 100 + p.size;  // count size and item size packed; lists are only skipped
      } else if (n >= 3) {
        p.name = std::string(tok[2]);
        if (!ply_type(std::string(tok[1]), p.size, p.kind))
          throw Error("read_cloud: " + where + "unknown property type '" + std::string(tok[1]) + "'");
      } else {
        throw Error("read_cloud: " + where + "bad property line");
      }
      h.elements.back().props.push_back(p);
    } else {
      throw Error("read_cloud: " + where + "unexpected PLY header line '" + std::string(line.substr(0, 40)) + "'");
    }
  }
  if (!format_seen) throw Error("read_cloud: " + src.name() + ": PLY header without a format line");
  h.header_bytes = pos;
  return h;
}

double read_scalar(const unsigned char* p, const PlyProperty& prop, bool swap) {
  unsigned char b[8];
  std::memcpy(b, p, prop.size);
  if (swap) std::reverse(b, b + prop.size);
  switch (prop.kind) {
    case 'f':
      if (prop.size == 4) { float f; std::memcpy(&f, b, 4); return f; }
      { double d; std::memcpy(&d, b, 8); return d; }
    case 'i':
      if (prop.size == 1) { std::int8_t v; std::memcpy(&v, b, 1); return v; }
      if (prop.size == 2) { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      { std::int32_t v; std::memcpy(&v, b, 4); return v; }
    default:
      if (prop.size == 1) { std::uint8_t v; std::memcpy(&v, b, 1); return v; }
      if (prop.size == 2) { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
  }
}

bool host_little_endian() {
  const std::uint16_t one = 1;
  unsigned char c;
  std::memcpy(&c, &one, 1);
  return c == 1;
}

// Throws for the first vertex of v[0, m) (vertex `first` is v[0]) with a non-finite
// coordinate or one beyond +-1e15; returns when there is none.
void check_vertices(const Eigen::Vector3d* v, std::size_t m, unsigned long long first, const std::string& name) {
  bool bad = false;
  const double* d = m ? v[0].data() : nullptr;
  for (std::size_t k = 0; k < 3 * m; ++k) bad |= !(std::abs(d[k]) <= detail::max_coordinate);
  for (std::size_t k = 0; bad && k < m; ++k) {
    if (!v[k].allFinite())
      throw Error("read_cloud: " + name + ": vertex " + std::to_string(first + k) + " has a non-finite coordinate");
    if (v[k].cwiseAbs().maxCoeff() > detail::max_coordinate)
      throw Error("read_cloud: " + name + ": point " + std::to_string(first + k + 1) +
                  " has a coordinate beyond +-1e15 (corrupt file?)");
  }
}

// Reads up to `want` bytes at offset `at` (again after a signal); returns how many it got:
// fewer at the end of the file or on an error.
std::size_t pread_full(int fd, void* buf, std::size_t want, unsigned long long at) {
  char* p = static_cast<char*>(buf);
  std::size_t got_all = 0;
  while (got_all < want) {
    const ssize_t got = ::pread(fd, p + got_all, want - got_all, static_cast<off_t>(at + got_all));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    got_all += std::size_t(got);
  }
  return got_all;
}

// Packed little-endian doubles x, y, z in a regular file, from the source's offset on:
// each chunk is read with pread straight into the (aligned) chunk, in parts that the
// threads read and check side by side. The copy out of the page cache is most of a pass
// over a binary cloud, and one thread alone cannot keep up with the slab tests after it.
std::size_t read_packed_file(Source& src, unsigned long long count, const CloudReadOptions& opt, Chunker& out) {
  const int fd = src.regular_fd();
  const unsigned long long start = src.offset();
  const std::size_t chunk = std::max<std::size_t>(opt.chunk_points, 1);
  const std::size_t workers =
      opt.threads > 0 ? std::size_t(opt.threads) : std::max(1u, std::thread::hardware_concurrency());
  unsigned long long done = 0;
  while (done < count) {
    std::size_t m = static_cast<std::size_t>(std::min<unsigned long long>(chunk, count - done));
    Eigen::Vector3d* dst = out.room(m);
    const std::size_t parts = std::max<std::size_t>(1, std::min(workers, m / 16384));
    std::vector<char> short_read(parts, 0), bad(parts, 0);
    detail::parallel_for(parts, opt.threads, [&](std::size_t t) {
      const std::size_t a = m * t / parts, b = m * (t + 1) / parts;
      if (pread_full(fd, dst + a, 24 * (b - a), start + 24 * (done + a)) < 24 * (b - a)) {
        short_read[t] = 1;
        return;
      }
      try {
        check_vertices(dst + a, b - a, done + a, src.name());
      } catch (const Error&) {
        bad[t] = 1;
      }
    });
    for (std::size_t t = 0; t < parts; ++t) {
      const std::size_t a = m * t / parts, b = m * (t + 1) / parts;
      if (short_read[t])
        throw Error("read_cloud: " + src.name() + ": PLY file ends or cannot be read after at most " +
                    std::to_string(done + a) + " of " + std::to_string(count) + " vertices (truncated file?)");
      if (bad[t]) check_vertices(dst + a, b - a, done + a, src.name());  // throws the first bad vertex's message
    }
    out.commit();
    done += m;
  }
  out.flush();
  return out.total();
}

// `fn` receives the points checked against max_coordinate; `raw` unchecked (the packed
// binary path checks while it reads).
std::size_t read_ply(Source& src, const CloudReadOptions& opt, const PointChunkFn& fn, const PointChunkFn& raw) {
  const PlyHeader h = parse_ply_header(src);
  const std::string& name = src.name();
  std::size_t vi = h.elements.size();
  for (std::size_t i = 0; i < h.elements.size(); ++i)
    if (h.elements[i].name == "vertex") { vi = i; break; }
  if (vi == h.elements.size()) throw Error("read_cloud: " + name + ": PLY file without a vertex element");
  if (vi != 0) throw Error("read_cloud: " + name + ": PLY vertex element must come first");
  const PlyElement& ve = h.elements[vi];
  int ix = -1, iy = -1, iz = -1;
  std::size_t record = 0;
  std::vector<std::size_t> offset;
  for (std::size_t i = 0; i < ve.props.size(); ++i) {
    const auto& p = ve.props[i];
    if (p.list) throw Error("read_cloud: " + name + ": list property '" + p.name + "' in the PLY vertex element is not supported");
    offset.push_back(record);
    record += static_cast<std::size_t>(p.size);
    if (p.name == "x") ix = static_cast<int>(i);
    if (p.name == "y") iy = static_cast<int>(i);
    if (p.name == "z") iz = static_cast<int>(i);
  }
  if (ix < 0 || iy < 0 || iz < 0) throw Error("read_cloud: " + name + ": PLY vertex element lacks x, y or z");
  if (ve.count == 0) throw Error("read_cloud: " + name + ": no points (PLY header declares 0 vertices)");
  if (ve.count > opt.max_points)
    throw Error("read_cloud: " + name + ": PLY header declares " + std::to_string(ve.count) + " vertices, more than the limit of " +
                std::to_string(opt.max_points));
  if (src.size() >= 0) {
    const unsigned long long body = static_cast<unsigned long long>(src.size()) - h.header_bytes;
    const unsigned long long min_bytes = h.format == PlyFormat::ascii ? ve.count * 6ULL : ve.count * record;
    if (min_bytes > body)
      throw Error("read_cloud: " + name + ": PLY header declares " + std::to_string(ve.count) + " vertices but the file holds " +
                  (h.format == PlyFormat::ascii ? "far fewer" : "only " + std::to_string(body / record)) + " (truncated file?)");
  }
  Chunker out(fn, opt.chunk_points);
  src.consume(h.header_bytes);
  if (h.format == PlyFormat::ascii) {
    std::size_t line_no = h.header_lines;
    std::size_t start = 0;
    unsigned long long done = 0;
    bool eof = false;
    std::string last;  // the last line when the file does not end with '\n'
    std::string_view buf = src.bytes();
    std::vector<double> vals(ve.props.size());
    while (done < ve.count) {
      std::size_t nl = buf.find('\n', start);
      if (nl == std::string::npos) {
        if (eof) {
          if (start < buf.size() && last.empty()) {
            last.assign(buf.substr(start));
            last.push_back('\n');
            buf = last;
            start = 0;
            continue;
          }
          throw Error("read_cloud: " + name + ": PLY file ends after " + std::to_string(done) + " of " +
                      std::to_string(ve.count) + " vertices (truncated file?)");
        }
        if (buf.size() - start > max_line) fail_line(name, line_no + 1, "line longer than " + std::to_string(max_line) + " characters");
        src.consume(start);
        start = 0;
        if (src.fetch(block_size) == 0) eof = true;
        buf = src.bytes();
        continue;
      }
      ++line_no;
      std::string_view line = trim(buf.substr(start, nl - start));
      start = nl + 1;
      if (line.empty()) continue;
      std::size_t i = 0;
      for (std::size_t k = 0; k < vals.size(); ++k) {
        while (i < line.size() && is_space(line[i])) ++i;
        const std::size_t s = i;
        while (i < line.size() && !is_space(line[i])) ++i;
        if (s == i) fail_line(name, line_no, "expected " + std::to_string(vals.size()) + " vertex values, found " + std::to_string(k));
        if (!parse_double(line.substr(s, i - s), vals[k]))
          fail_line(name, line_no, "expected a number, found '" + std::string(line.substr(s, std::min<std::size_t>(i - s, 40))) + "'");
      }
      const double x = vals[ix], y = vals[iy], z = vals[iz];
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) fail_line(name, line_no, "non-finite coordinate");
      out.add(x, y, z);
      ++done;
    }
  } else {
    const bool swap = (h.format == PlyFormat::binary_le) != host_little_endian();
    unsigned long long done = 0;
    const PlyProperty px = ve.props[ix], py = ve.props[iy], pz = ve.props[iz];
    const std::size_t ox = offset[ix], oy = offset[iy], oz = offset[iz];
    const bool same = !swap && px.kind == 'f' && py.kind == 'f' && pz.kind == 'f' && px.size == py.size && py.size == pz.size;
    // Converts n records at r into dst, one type test per block rather than per value.
    const auto convert = [&](const unsigned char* r, std::size_t n, Eigen::Vector3d* dst) {
      if (same && px.size == 8 && record == 24 && ox == 0 && oy == 8 && oz == 16) {
        static_assert(sizeof(Eigen::Vector3d) == 24, "packed Vector3d");
        std::memcpy(static_cast<void*>(dst), r, n * 24);
      } else if (same && px.size == 8) {
        for (std::size_t k = 0; k < n; ++k, r += record) {
          double v[3];
          std::memcpy(&v[0], r + ox, 8);
          std::memcpy(&v[1], r + oy, 8);
          std::memcpy(&v[2], r + oz, 8);
          dst[k] = Eigen::Vector3d(v[0], v[1], v[2]);
        }
      } else if (same) {
        for (std::size_t k = 0; k < n; ++k, r += record) {
          float f[3];
          std::memcpy(&f[0], r + ox, 4);
          std::memcpy(&f[1], r + oy, 4);
          std::memcpy(&f[2], r + oz, 4);
          dst[k] = Eigen::Vector3d(f[0], f[1], f[2]);
        }
      } else {
        for (std::size_t k = 0; k < n; ++k, r += record)
          dst[k] = Eigen::Vector3d(read_scalar(r + ox, px, swap), read_scalar(r + oy, py, swap), read_scalar(r + oz, pz, swap));
      }
    };
    // Packed little-endian doubles x, y, z (what write_cloud and many scanners write): one
    // pass checks a whole chunk, which then goes to the callback straight from the read
    // buffer when it is 8-byte aligned.
    if (same && px.size == 8 && record == 24 && ox == 0 && oy == 8 && oz == 16) {
      Chunker direct(raw, opt.chunk_points);
      const std::size_t chunk = std::max<std::size_t>(opt.chunk_points, 1);
      if (src.regular_fd() >= 0) return read_packed_file(src, ve.count, opt, direct);
      while (done < ve.count) {
        const std::size_t want = static_cast<std::size_t>(std::min<unsigned long long>(chunk, ve.count - done));
        while (src.bytes().size() < want * 24 && src.fetch(want * 24 - src.bytes().size()) > 0) {
        }
        const std::size_t n = std::min(want, src.bytes().size() / 24);
        if (n == 0)
          throw Error("read_cloud: " + name + ": PLY file ends after " + std::to_string(done) + " of " +
                      std::to_string(ve.count) + " vertices (truncated file?)");
        const char* r = src.bytes().data();
        if (reinterpret_cast<std::uintptr_t>(r) % alignof(Eigen::Vector3d) == 0) {
          check_vertices(reinterpret_cast<const Eigen::Vector3d*>(r), n, done, name);
          direct.add_many(reinterpret_cast<const Eigen::Vector3d*>(r), n);
        } else {
          // Copied in blocks that stay in the cache while they are checked.
          for (std::size_t k = 0; k < n;) {
            std::size_t m = std::min<std::size_t>(n - k, 2048);
            Eigen::Vector3d* dst = direct.room(m);
            std::memcpy(static_cast<void*>(dst), r + 24 * k, 24 * m);
            check_vertices(dst, m, done + k, name);
            direct.commit();
            k += m;
          }
        }
        done += n;
        src.consume(n * 24);
      }
      direct.flush();
      return direct.total();
    }
    while (done < ve.count) {
      const std::size_t avail = src.bytes().size() / record;
      if (avail == 0) {
        const std::size_t want = std::max<std::size_t>(record, std::min<unsigned long long>((ve.count - done) * record, block_size));
        if (src.fetch(want) == 0)
          throw Error("read_cloud: " + name + ": PLY file ends after " + std::to_string(done) + " of " +
                      std::to_string(ve.count) + " vertices (truncated file?)");
        continue;
      }
      std::size_t n = static_cast<std::size_t>(std::min<unsigned long long>(avail, ve.count - done));
      const unsigned char* r = reinterpret_cast<const unsigned char*>(src.bytes().data());
      Eigen::Vector3d* dst = out.room(n);
      convert(r, n, dst);
      // One branch-free test over the block; the vertex is looked for only when it fails.
      bool bad = false;
      const double* d = dst[0].data();
      for (std::size_t k = 0; k < 3 * n; ++k) bad |= !(std::abs(d[k]) <= std::numeric_limits<double>::max());
      for (std::size_t k = 0; bad && k < n; ++k)
        if (!dst[k].allFinite())
          throw Error("read_cloud: " + name + ": vertex " + std::to_string(done + k) + " has a non-finite coordinate");
      out.commit();
      done += n;
      src.consume(n * record);
    }
  }
  out.flush();
  return out.total();
}

CloudFormat format_of(const std::string& path, std::string_view head) {
  if (path != "-") {
    const std::string ext = extension(path);
    if (ext == "ply") return CloudFormat::ply;
    if (ext == "csv") return CloudFormat::csv;
    if (ext == "xyz" || ext == "asc" || ext == "txt" || ext == "pts" || ext == "xyzn") return CloudFormat::xyz;
    if (ext == "stl" || ext == "obj" || ext == "off")
      throw Error("read_cloud: " + path + ": is a mesh, not a point cloud");
  }
  if (head.compare(0, 3, "ply") == 0) return CloudFormat::ply;
  if (path != "-" && !extension(path).empty())
    throw Error("read_cloud: " + path + ": unknown point cloud extension '." + extension(path) +
                "' (use .xyz .asc .txt .pts .csv .ply)");
  return CloudFormat::xyz;
}

}  // namespace

namespace {
std::size_t read_source(Source& src, const std::string& path, const PointChunkFn& on_chunk,
                        const CloudReadOptions& options) {
  src.fetch(1 << 16);
  std::string_view buf = src.bytes();
  if (buf.empty()) throw Error("read_cloud: " + src.name() + ": empty file");
  CloudFormat format = options.format;
  if (format == CloudFormat::automatic) format = format_of(path, buf);
  if (format != CloudFormat::ply) {
    if (const char* why = detail::text_encoding_problem(buf)) throw Error("read_cloud: " + src.name() + ": " + why);
    if (buf.compare(0, 3, "\xEF\xBB\xBF") == 0) src.consume(3);  // a UTF-8 byte-order mark
  }
  std::size_t seen = 0;
  const PointChunkFn checked = [&](const Eigen::Vector3d* p, std::size_t n) {
    bool beyond = false;
    const double* d = n ? p[0].data() : nullptr;
    for (std::size_t i = 0; i < 3 * n; ++i) beyond |= std::abs(d[i]) > detail::max_coordinate;
    for (std::size_t i = 0; beyond && i < n; ++i)
      if (p[i].cwiseAbs().maxCoeff() > detail::max_coordinate)
        throw Error("read_cloud: " + src.name() + ": point " + std::to_string(seen + i + 1) +
                    " has a coordinate beyond +-1e15 (corrupt file?)");
    seen += n;
    on_chunk(p, n);
  };
  switch (format) {
    case CloudFormat::ply: return read_ply(src, options, checked, on_chunk);
    case CloudFormat::csv: return read_text(src, true, options, checked);
    default: return read_text(src, false, options, checked);
  }
}
}  // namespace

std::size_t read_cloud_chunks(const std::string& path, const PointChunkFn& on_chunk, const CloudReadOptions& options) {
  Source src(path);
  return read_source(src, path, on_chunk, options);
}

namespace {

// Where x, y and z lie in the vertex records of a binary PLY file whose vertices come
// first and fill the file as its header says (what pread can read anywhere).
struct BinaryVertices {
  unsigned long long start = 0, count = 0;  // first vertex's file offset, vertices
  std::size_t record = 0;                   // bytes per vertex
  std::size_t offset[3] = {0, 0, 0};        // of x, y, z in a record
  PlyProperty prop[3];                      // their types
  bool swap = false;                        // byte order other than the host's
  // Little-endian doubles x, y, z and nothing else: a record is an Eigen::Vector3d.
  bool packed() const {
    return !swap && record == 24 && offset[0] == 0 && offset[1] == 8 && offset[2] == 16 &&
           std::all_of(prop, prop + 3, [](const PlyProperty& p) { return p.kind == 'f' && p.size == 8; });
  }
};

// The layout of `src`'s vertices when it is a regular binary PLY file as above, else
// nothing. A header that does not parse is nothing too: the reader proper reports it.
std::optional<BinaryVertices> binary_vertices(Source& src, const std::string& path, const CloudReadOptions& options) {
  try {
    if (src.regular_fd() < 0 || src.fetch(1 << 16) == 0) return std::nullopt;
    if ((options.format == CloudFormat::automatic ? format_of(path, src.bytes()) : options.format) != CloudFormat::ply)
      return std::nullopt;
    const PlyHeader h = parse_ply_header(src);
    if (h.format == PlyFormat::ascii || h.elements.empty() || h.elements[0].name != "vertex") return std::nullopt;
    const PlyElement& ve = h.elements[0];
    BinaryVertices v;
    bool found[3] = {false, false, false};
    for (const auto& p : ve.props) {
      if (p.list) return std::nullopt;
      for (int c = 0; c < 3; ++c)
        if (p.name.size() == 1 && p.name[0] == char('x' + c)) {
          v.prop[c] = p;
          v.offset[c] = v.record;
          found[c] = true;
        }
      v.record += static_cast<std::size_t>(p.size);
    }
    const unsigned long long body = static_cast<unsigned long long>(src.size()) - h.header_bytes;
    if (!found[0] || !found[1] || !found[2] || v.record == 0 || ve.count == 0 || ve.count > options.max_points ||
        body / v.record < ve.count)
      return std::nullopt;
    v.start = h.header_bytes;
    v.count = ve.count;
    v.swap = (h.format == PlyFormat::binary_le) != host_little_endian();
    return v;
  } catch (const Error&) {
    return std::nullopt;
  }
}

}  // namespace

std::size_t read_cloud_chunks_parallel(const std::string& path, const ChunkWorkFn& work, const IndexedChunkFn& merge,
                                       const CloudReadOptions& options) {
  const std::size_t chunk = std::max<std::size_t>(options.chunk_points, 1);
  // Packed doubles in a regular file: pread anywhere, no conversion.
  std::unique_ptr<Source> src;
  std::optional<BinaryVertices> layout;
  if (path != "-") {
    src = std::make_unique<Source>(path);
    layout = binary_vertices(*src, path, options);
  }
  const bool packed = layout && layout->packed();
  const unsigned long long count = packed ? layout->count : 0, start = packed ? layout->start : 0;
  const int fd = packed ? src->regular_fd() : -1;
  if (count == 0) {
    // Anything else (its errors included) as read_cloud_chunks reads it.
    std::size_t index = 0;
    return read_cloud_chunks(
        path,
        [&](const Eigen::Vector3d* p, std::size_t n) {
          work(index, p, n, options.threads);
          merge(index, p, n);
          ++index;
        },
        options);
  }
  const std::string name = src->name();
  const std::size_t chunks = static_cast<std::size_t>((count + chunk - 1) / chunk);
  const std::size_t workers = std::min<std::size_t>(
      chunks, options.threads > 0 ? std::size_t(options.threads) : std::max(1u, std::thread::hardware_concurrency()));
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::condition_variable merged_one;
  std::size_t next_merge = 0;
  std::size_t first_bad = chunks;  // lowest chunk that failed
  std::exception_ptr error;        // its error
  const auto run = [&] {
    std::vector<Eigen::Vector3d> buf;
    for (std::size_t k; (k = next++) < chunks;) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (k > first_bad) break;  // an earlier chunk failed: no use reading on
      }
      const unsigned long long first = static_cast<unsigned long long>(k) * chunk;
      const std::size_t m = static_cast<std::size_t>(std::min<unsigned long long>(chunk, count - first));
      try {
        buf.resize(m);
        const std::size_t got = pread_full(fd, buf.data(), 24 * m, start + 24 * first);
        if (got < 24 * m)
          throw Error("read_cloud: " + name + ": PLY file ends or cannot be read after at most " +
                      std::to_string(first + got / 24) + " of " + std::to_string(count) +
                      " vertices (truncated file?)");
        check_vertices(buf.data(), m, first, name);
        work(k, buf.data(), m, 1);
        // Merged in file order: wait for the chunks before.
        std::unique_lock<std::mutex> lock(mutex);
        merged_one.wait(lock, [&] { return next_merge == k || first_bad < k; });
        if (first_bad < k) break;
        lock.unlock();
        merge(k, buf.data(), m);
        lock.lock();
        ++next_merge;
        merged_one.notify_all();
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (k < first_bad) {
          first_bad = k;
          error = std::current_exception();
        }
        merged_one.notify_all();
        break;
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(run);
  run();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return static_cast<std::size_t>(count);
}

CloudPeek peek_cloud(const std::string& path, std::size_t count, const CloudReadOptions& options) {
  CloudPeek out;
  if (path == "-" || count == 0) return out;
  try {
    Source src(path);
    const auto v = binary_vertices(src, path, options);
    if (!v || v->record > 4096) return out;
    const unsigned long long m = std::min<unsigned long long>(count, v->count);
    unsigned char rec[4096];
    out.points.reserve(static_cast<std::size_t>(m));
    for (unsigned long long i = 0; i < m; ++i) {
      // Vertex i of m evenly spaced ones, moved within its stride by a golden-ratio
      // sequence: no lattice from a regular scan order, and the same points every time.
      const double jitter = std::fmod(0.5 + 0.6180339887498949 * double(i), 1.0);
      const unsigned long long k = std::min<unsigned long long>(
          v->count - 1, static_cast<unsigned long long>((double(i) + jitter) * double(v->count) / double(m)));
      if (pread_full(src.regular_fd(), rec, v->record, v->start + k * v->record) < v->record) return {};
      const Eigen::Vector3d p(read_scalar(rec + v->offset[0], v->prop[0], v->swap),
                              read_scalar(rec + v->offset[1], v->prop[1], v->swap),
                              read_scalar(rec + v->offset[2], v->prop[2], v->swap));
      if (p.allFinite() && p.cwiseAbs().maxCoeff() <= detail::max_coordinate) out.points.push_back(p);
    }
    out.total = v->count;
  } catch (const Error&) {
    return {};
  }
  return out;
}

Cloud read_cloud(const std::string& path, const CloudReadOptions& options) {
  Cloud cloud;
  read_cloud_chunks(path, [&](const Eigen::Vector3d* p, std::size_t n) { cloud.points.insert(cloud.points.end(), p, p + n); },
                    options);
  return cloud;
}

Cloud parse_cloud(std::string_view bytes, const std::string& name, const CloudReadOptions& options) {
  Source src(bytes, name);
  Cloud cloud;
  read_source(src, name, [&](const Eigen::Vector3d* p, std::size_t n) { cloud.points.insert(cloud.points.end(), p, p + n); },
              options);
  return cloud;
}

void write_cloud(const std::string& path, const Cloud& cloud) {
  std::FILE* f = path == "-" ? stdout : std::fopen(path.c_str(), "wb");
  if (!f) throw Error("write_cloud: " + path + ": cannot open for writing: " + std::strerror(errno));
  bool ok = true;
  if (extension(path) == "ply") {
    std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(cloud.points.size()) +
                         "\nproperty double x\nproperty double y\nproperty double z\nend_header\n";
    ok = std::fwrite(header.data(), 1, header.size(), f) == header.size();
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "packed Vector3d");
    if (ok && !cloud.points.empty())
      ok = std::fwrite(cloud.points.data(), sizeof(Eigen::Vector3d), cloud.points.size(), f) == cloud.points.size();
  } else {
    std::string out;
    char b[32];
    for (const auto& p : cloud.points) {
      for (int k = 0; k < 3; ++k) {
        const auto r = std::to_chars(b, b + sizeof b, p[k]);
        out.append(b, r.ptr);
        out += k == 2 ? '\n' : ' ';
      }
      if (out.size() > (1 << 22)) {
        ok = ok && std::fwrite(out.data(), 1, out.size(), f) == out.size();
        out.clear();
      }
    }
    ok = ok && std::fwrite(out.data(), 1, out.size(), f) == out.size();
  }
  if (path == "-") ok = ok && std::fflush(f) == 0;
  else ok = (std::fclose(f) == 0) && ok;
  if (!ok) throw Error("write_cloud: " + path + ": write error");
}

}  // namespace section
