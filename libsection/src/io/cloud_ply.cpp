// SPDX-License-Identifier: GPL-3.0-or-later
// The PLY cloud reader: the vertices of an ascii or binary (little or big endian) PLY file.
#include "io/cloud_readers.h"

#include "detail/parallel.h"
#include "io/formats.h"
#include "io/ply.h"
#include "io/text.h"
#include "section/error.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace section::detail {

namespace {

const PlyMessages messages{"read_cloud: ", false};

[[noreturn]] void fail_ends(const std::string& name, unsigned long long done, unsigned long long count) {
  throw Error("read_cloud: " + name + ": PLY file ends after " + std::to_string(done) + " of " +
              std::to_string(count) + " vertices (truncated file?)");
}

// The vertex element of a PLY cloud and where x, y and z lie in it.
struct VertexLayout {
  const PlyElement* vertex = nullptr;
  int ix = -1, iy = -1, iz = -1;    // properties of x, y, z
  std::size_t record = 0;           // bytes per binary vertex
  std::vector<std::size_t> offset;  // of each property in a binary vertex
  // Little-endian doubles x, y, z and nothing else.
  bool packed(bool swap) const {
    const auto& p = vertex->props;
    for (int i : {ix, iy, iz})
      if (swap || p[i].kind != 'f' || p[i].size != 8) return false;
    return record == 24 && offset[ix] == 0 && offset[iy] == 8 && offset[iz] == 16;
  }
};

void check_binary_size(const PlyHeader& h, const VertexLayout& l, unsigned long long body,
                       const std::string& name);

// The vertex element of `h` (it must come first, hold x, y and z and no lists), checked
// against the limits and against the size of the file when it is known.
VertexLayout vertex_layout(const PlyHeader& h, const ByteSource& src, const CloudReadOptions& opt) {
  const std::string& name = src.name();
  std::size_t vi = h.elements.size();
  for (std::size_t i = 0; i < h.elements.size(); ++i)
    if (h.elements[i].name == "vertex") {
      vi = i;
      break;
    }
  if (vi == h.elements.size()) throw Error("read_cloud: " + name + ": PLY file without a vertex element");
  if (vi != 0) throw Error("read_cloud: " + name + ": PLY vertex element must come first");
  VertexLayout l;
  l.vertex = &h.elements[vi];
  const PlyElement& ve = *l.vertex;
  for (std::size_t i = 0; i < ve.props.size(); ++i) {
    const auto& p = ve.props[i];
    if (p.list())
      throw Error("read_cloud: " + name + ": list property '" + p.name +
                  "' in the PLY vertex element is not supported");
    l.offset.push_back(l.record);
    l.record += static_cast<std::size_t>(p.size);
    if (p.name == "x") l.ix = static_cast<int>(i);
    if (p.name == "y") l.iy = static_cast<int>(i);
    if (p.name == "z") l.iz = static_cast<int>(i);
  }
  if (l.ix < 0 || l.iy < 0 || l.iz < 0)
    throw Error("read_cloud: " + name + ": PLY vertex element lacks x, y or z");
  if (ve.count == 0) throw Error("read_cloud: " + name + ": no points (PLY header declares 0 vertices)");
  if (ve.count > opt.max_points)
    throw Error("read_cloud: " + name + ": PLY header declares " + std::to_string(ve.count) +
                " vertices, more than the limit of " + std::to_string(opt.max_points));
  if (src.size() >= 0) {
    const bool ascii = h.format == PlyFormat::ascii;
    const unsigned long long body = static_cast<unsigned long long>(src.size()) - h.bytes;
    const unsigned long long min_bytes = ascii ? ve.count * 6ULL : ve.count * l.record;
    if (min_bytes > body)
      throw Error("read_cloud: " + name + ": PLY header declares " + std::to_string(ve.count) +
                  " vertices but the file holds " +
                  (ascii ? "far fewer" : "only " + std::to_string(body / l.record)) + " (truncated file?)");
    if (!ascii) check_binary_size(h, l, body, name);
  }
  return l;
}

// A binary file longer than its header says (a vertex count written too small) is refused,
// not read in part: the elements after the vertices must fill the rest exactly. Elements
// with lists (faces) are not checked.
void check_binary_size(const PlyHeader& h, const VertexLayout& l, unsigned long long body,
                       const std::string& name) {
  unsigned long long declared = l.vertex->count * l.record;
  for (std::size_t e = 1; e < h.elements.size(); ++e) {
    unsigned long long record = 0;
    for (const PlyProperty& p : h.elements[e].props) {
      if (p.list() && h.elements[e].count > 0) return;
      record += static_cast<unsigned long long>(p.size);
    }
    declared += h.elements[e].count * record;
  }
  if (body <= declared) return;
  throw Error("read_cloud: " + name + ": the file holds " + std::to_string(body - declared) +
              " bytes more than its PLY header declares (" + std::to_string(l.vertex->count) + " vertices" +
              (h.elements.size() > 1 ? " and the elements after them" : std::string()) + ", " +
              std::to_string(body / l.record) + " would fit): a wrong vertex count?");
}

// The lines after the vertices of an ascii file, from line `line_no` on: one per element
// the header declares after the vertices (blank lines skipped), and nothing more, so that a
// vertex count written too small is refused rather than read in part.
void check_ascii_rest(ByteSource& src, const PlyHeader& h, std::size_t line_no) {
  unsigned long long declared = 0;
  for (std::size_t e = 1; e < h.elements.size(); ++e) declared += h.elements[e].count;
  std::string_view line;
  unsigned long long lines = 0;
  while (src.next_line(line, max_line)) {
    ++line_no;
    if (!trim(line).empty() && ++lines > declared)
      fail_line(src.name(), line_no,
                "more lines than the PLY header declares (" + std::to_string(h.elements[0].count) +
                    " vertices" + (declared ? " and " + std::to_string(declared) + " more elements" : "") +
                    "): a wrong vertex count?");
  }
}

// Ascii vertices, one a line (blank lines skipped); line numbers count from the header's.
std::size_t read_ascii(ByteSource& src, const PlyHeader& h, const VertexLayout& l, Chunker& out) {
  const std::string& name = src.name();
  const unsigned long long count = l.vertex->count;
  std::size_t line_no = h.lines;
  std::size_t start = 0;
  unsigned long long done = 0;
  bool eof = false;
  std::string last;  // the last line when the file does not end with '\n'
  std::string_view buf = src.bytes();
  std::vector<double> vals(l.vertex->props.size());
  while (done < count) {
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
        fail_ends(name, done, count);
      }
      if (buf.size() - start > max_line)
        fail_line(name, line_no + 1, "line longer than " + std::to_string(max_line) + " characters");
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
      if (s == i)
        fail_line(name, line_no,
                  "expected " + std::to_string(vals.size()) + " vertex values, found " + std::to_string(k));
      if (!parse_double(line.substr(s, i - s), vals[k]))
        fail_line(name, line_no,
                  "expected a number, found '" +
                      std::string(line.substr(s, std::min<std::size_t>(i - s, 40))) + "'");
    }
    const double x = vals[l.ix], y = vals[l.iy], z = vals[l.iz];
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      fail_line(name, line_no, "non-finite coordinate");
    out.add(x, y, z);
    ++done;
  }
  src.consume(last.empty() ? start : src.bytes().size());
  return line_no;
}

// Packed little-endian doubles x, y, z in a regular file, from the source's offset on:
// each chunk is read with pread straight into the (aligned) chunk, in parts that the
// threads read and check side by side. The copy out of the page cache is most of a pass
// over a binary cloud, and one thread alone cannot keep up with the slab tests after it.
void read_packed_file(ByteSource& src, unsigned long long count, const CloudReadOptions& opt, Chunker& out) {
  const int fd = src.regular_fd();
  const unsigned long long start = src.offset();
  const std::size_t chunk = std::max<std::size_t>(opt.chunk_points, 1);
  const std::size_t workers = worker_count(opt.threads);
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
                    std::to_string(done + a) + " of " + std::to_string(count) +
                    " vertices (truncated file?)");
      if (bad[t])
        check_vertices(dst + a, b - a, done + a, src.name());  // throws the first bad vertex's message
    }
    out.commit();
    done += m;
  }
}

// Packed little-endian doubles x, y, z (what write_cloud and many scanners write): one pass
// checks a whole chunk, which then goes to the callback straight from the read buffer when
// it is 8-byte aligned; a regular file is read by read_packed_file.
std::size_t read_packed(ByteSource& src, unsigned long long count, const CloudReadOptions& opt,
                        const PointChunkFn& raw) {
  const std::string& name = src.name();
  Chunker direct(raw, opt.chunk_points);
  const std::size_t chunk = std::max<std::size_t>(opt.chunk_points, 1);
  if (src.regular_fd() >= 0) {
    read_packed_file(src, count, opt, direct);
    direct.flush();
    return direct.total();
  }
  unsigned long long done = 0;
  while (done < count) {
    const std::size_t want = static_cast<std::size_t>(std::min<unsigned long long>(chunk, count - done));
    while (src.bytes().size() < want * 24 && src.fetch(want * 24 - src.bytes().size()) > 0) {
    }
    const std::size_t n = std::min(want, src.bytes().size() / 24);
    if (n == 0) fail_ends(name, done, count);
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

// n records at r into dst, with scalars of type T at offsets o.
template <class T>
void gather(const unsigned char* r, std::size_t n, std::size_t record, const std::size_t o[3],
            Eigen::Vector3d* dst) {
  for (std::size_t k = 0; k < n; ++k, r += record) {
    T v[3];
    for (int c = 0; c < 3; ++c) std::memcpy(&v[c], r + o[c], sizeof(T));
    dst[k] = Eigen::Vector3d(v[0], v[1], v[2]);
  }
}

// Binary vertices of any layout, converted a block at a time.
void read_binary(ByteSource& src, const PlyHeader& h, const VertexLayout& l, Chunker& out) {
  const std::string& name = src.name();
  const bool swap = h.swap();
  const unsigned long long count = l.vertex->count;
  const std::size_t record = l.record;
  const PlyProperty* p[3] = {&l.vertex->props[l.ix], &l.vertex->props[l.iy], &l.vertex->props[l.iz]};
  const std::size_t o[3] = {l.offset[l.ix], l.offset[l.iy], l.offset[l.iz]};
  const bool same = !swap && p[0]->kind == 'f' && p[1]->kind == 'f' && p[2]->kind == 'f' &&
                    p[0]->size == p[1]->size && p[1]->size == p[2]->size;
  // One type test per block rather than per value.
  const auto convert = [&](const unsigned char* r, std::size_t n, Eigen::Vector3d* dst) {
    if (same && p[0]->size == 8) return gather<double>(r, n, record, o, dst);
    if (same) return gather<float>(r, n, record, o, dst);
    for (std::size_t k = 0; k < n; ++k, r += record)
      dst[k] = Eigen::Vector3d(ply_scalar(r + o[0], p[0]->size, p[0]->kind, swap),
                               ply_scalar(r + o[1], p[1]->size, p[1]->kind, swap),
                               ply_scalar(r + o[2], p[2]->size, p[2]->kind, swap));
  };
  unsigned long long done = 0;
  while (done < count) {
    const std::size_t avail = src.bytes().size() / record;
    if (avail == 0) {
      const std::size_t want =
          std::max<std::size_t>(record, std::min<unsigned long long>((count - done) * record, block_size));
      if (src.fetch(want) == 0) fail_ends(name, done, count);
      continue;
    }
    std::size_t n = static_cast<std::size_t>(std::min<unsigned long long>(avail, count - done));
    const unsigned char* r = reinterpret_cast<const unsigned char*>(src.bytes().data());
    Eigen::Vector3d* dst = out.room(n);
    convert(r, n, dst);
    // One branch-free test over the block; the vertex is looked for only when it fails.
    bool bad = false;
    const double* d = dst[0].data();
    for (std::size_t k = 0; k < 3 * n; ++k) bad |= !(std::abs(d[k]) <= std::numeric_limits<double>::max());
    for (std::size_t k = 0; bad && k < n; ++k)
      if (!dst[k].allFinite())
        throw Error("read_cloud: " + name + ": vertex " + std::to_string(done + k) +
                    " has a non-finite coordinate");
    out.commit();
    done += n;
    src.consume(n * record);
  }
}

}  // namespace

std::size_t read_ply_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn& raw) {
  const PlyHeader h = read_ply_header(src, messages);
  const VertexLayout l = vertex_layout(h, src, opt);
  src.consume(h.bytes);
  if (h.format != PlyFormat::ascii && l.packed(h.swap())) return read_packed(src, l.vertex->count, opt, raw);
  Chunker out(fn, opt.chunk_points);
  if (h.format == PlyFormat::ascii)
    check_ascii_rest(src, h, read_ascii(src, h, l, out));
  else
    read_binary(src, h, l, out);
  out.flush();
  return out.total();
}

void check_vertices(const Eigen::Vector3d* v, std::size_t m, unsigned long long first,
                    const std::string& name) {
  // |x| <= max_coordinate, NaN not, as integers: a double's bits without the sign order
  // like its magnitude (a NaN's above every number's), so limit - bits turns negative
  // exactly where the test fails. Ors of differences pair up in vector registers; the
  // floating compare did not (6 % of `slice` on a 5 M point scan).
  std::uint64_t limit;
  std::memcpy(&limit, &detail::max_coordinate, sizeof limit);
  std::int64_t any = 0;
  const double* d = m ? v[0].data() : nullptr;
#pragma GCC unroll 8
  for (std::size_t k = 0; k < 3 * m; ++k) {
    std::uint64_t bits;
    std::memcpy(&bits, d + k, sizeof bits);
    any |= std::int64_t(limit - (bits & 0x7fffffffffffffffULL));
  }
  const bool bad = any < 0;
  for (std::size_t k = 0; bad && k < m; ++k) {
    if (!v[k].allFinite())
      throw Error("read_cloud: " + name + ": vertex " + std::to_string(first + k) +
                  " has a non-finite coordinate");
    if (v[k].cwiseAbs().maxCoeff() > detail::max_coordinate)
      throw Error("read_cloud: " + name + ": point " + std::to_string(first + k + 1) +
                  " has a coordinate beyond +-1e15 (corrupt file?)");
  }
}

bool BinaryVertices::packed() const {
  for (int c = 0; c < 3; ++c)
    if (kind[c] != 'f' || size[c] != 8) return false;
  return !swap && record == 24 && offset[0] == 0 && offset[1] == 8 && offset[2] == 16;
}

Eigen::Vector3d BinaryVertices::point(const unsigned char* r) const {
  return {ply_scalar(r + offset[0], size[0], kind[0], swap),
          ply_scalar(r + offset[1], size[1], kind[1], swap),
          ply_scalar(r + offset[2], size[2], kind[2], swap)};
}

std::optional<BinaryVertices> binary_vertices(ByteSource& src, const std::string& path,
                                              const CloudReadOptions& options) {
  try {
    if (src.regular_fd() < 0 || src.fetch(1 << 16) == 0) return std::nullopt;
    if (cloud_format(path, src.bytes(), options.format).cloud != CloudFormat::ply) return std::nullopt;
    const PlyHeader h = read_ply_header(src, messages);
    if (h.format == PlyFormat::ascii || h.elements.empty() || h.elements[0].name != "vertex")
      return std::nullopt;
    const PlyElement& ve = h.elements[0];
    BinaryVertices v;
    bool found[3] = {false, false, false};
    for (const auto& p : ve.props) {
      if (p.list()) return std::nullopt;
      for (int c = 0; c < 3; ++c)
        if (p.name.size() == 1 && p.name[0] == char('x' + c)) {
          v.size[c] = p.size;
          v.kind[c] = p.kind;
          v.offset[c] = v.record;
          found[c] = true;
        }
      v.record += static_cast<std::size_t>(p.size);
    }
    // Only a file its vertices fill exactly: the reader proper words what is wrong with another.
    const unsigned long long body = static_cast<unsigned long long>(src.size()) - h.bytes;
    if (!found[0] || !found[1] || !found[2] || v.record == 0 || ve.count == 0 ||
        ve.count > options.max_points || h.elements.size() != 1 || body / v.record != ve.count ||
        body % v.record != 0)
      return std::nullopt;
    v.start = h.bytes;
    v.count = ve.count;
    v.swap = h.swap();
    return v;
  } catch (const Error&) {
    return std::nullopt;
  }
}

}  // namespace section::detail
