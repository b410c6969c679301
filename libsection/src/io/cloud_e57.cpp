// SPDX-License-Identifier: GPL-3.0-or-later
// The E57 cloud reader (ASTM E2807-11, "Standard Specification for 3D Imaging Data
// Exchange, Version 1.0"), read from the standard directly: Debian 12 packages no E57
// library (libE57Format is not in it). An E57 file is a sequence of physical pages
// (usually 1024 bytes), each its logical bytes followed by their CRC-32C (big endian),
// checked here for every page read. The 48-byte file header (page 0) gives the page size
// and where the XML section lies (cloud_e57_xml.cpp reads it: the scans, their poses and
// their points' prototypes). A scan's points are a CompressedVector binary section: a
// 32-byte section header giving where its packets start, then data packets (index and
// empty packets are skipped), each holding one piece of every field's bytestream: a
// Float's IEEE values (4 or 8 bytes, little endian), an Integer's or ScaledInteger's
// values less its minimum, bit-packed least significant bit first in just enough bits for
// its range (the bitPackCodec). Points whose cartesianInvalidState (or
// sphericalInvalidState) is not 0 are dropped, and so are points with a NaN coordinate;
// each scan's pose is applied (x_file = R x_scan + t), so the scans come out merged in the
// file's frame, in file order.
#include "io/cloud_e57.h"
#include "io/cloud_readers.h"
#include "section/io/limits.h"

#include "section/error.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace section::detail {

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw Error("read_cloud: " + name + ": E57 " + what);
}

// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78): a table a byte at a time, or the
// SSE 4.2 instruction where the processor has it (50 times faster: the checksums of a
// 100 MB file take 10 ms, not 0.5 s).
std::uint32_t crc32c_table(const unsigned char* p, std::size_t n) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ ((c & 1) ? 0x82F63B78u : 0u);
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) c = table[(c ^ p[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SECTION_CRC32C_SSE42 1
__attribute__((target("sse4.2"))) std::uint32_t crc32c_sse42(const unsigned char* p, std::size_t n) {
  std::uint64_t c = 0xFFFFFFFFu;
  for (; n >= 8; p += 8, n -= 8)
    c = __builtin_ia32_crc32di(c, le<std::uint64_t>(reinterpret_cast<const char*>(p)));
  auto c32 = static_cast<std::uint32_t>(c);
  for (; n > 0; ++p, --n) c32 = __builtin_ia32_crc32qi(c32, *p);
  return c32 ^ 0xFFFFFFFFu;
}

#endif

// The logical bytes of an E57 file: its pages without their checksums, each page's
// checksum checked when it is first read. A file is read with pread, blocks of pages at a
// time; a source in memory (parse_cloud) is read whole.
class Pages {
public:
  Pages(ByteSource& src, std::uint64_t page) : name_(src.name()), fd_(src.regular_fd()), page_(page) {
    if (fd_ < 0) {
      while (src.fetch(block_size) > 0) {
      }
      whole_ = src.bytes();
      size_ = whole_.size();
    } else {
      size_ = static_cast<std::uint64_t>(src.size());
    }
  }
  std::uint64_t size() const { return size_; }
  std::uint64_t logical(std::uint64_t physical) const {
    return physical / page_ * (page_ - 4) + physical % page_;
  }
  std::uint64_t physical(std::uint64_t logical) const {
    return logical / (page_ - 4) * page_ + logical % (page_ - 4);
  }
  /// Copies the `n` logical bytes at logical offset `at` to `out`.
  void read(std::uint64_t at, std::size_t n, char* out) {
    const std::uint64_t data = page_ - 4;
    while (n > 0) {
      const std::uint64_t index = at / data, in = at % data;
      const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(n, data - in));
      std::memcpy(out, page(index) + in, take);
      out += take;
      at += take;
      n -= take;
    }
  }

private:
  // Page `index`, checked; loads the block of pages starting there when it is not at hand.
  const char* page(std::uint64_t index) {
    if (index >= first_ && index < first_ + count_) return block_ + (index - first_) * page_;
    const std::uint64_t at = index * page_;
    if (at >= size_)
      fail(name_, "file ends at byte " + std::to_string(size_) + ", before its page " +
                      std::to_string(index) + " (truncated file?)");
    const std::uint64_t want = std::min<std::uint64_t>(size_ - at, 256 * page_);
    if (want < page_)
      fail(name_, "file ends at byte " + std::to_string(size_) + ", inside its page " +
                      std::to_string(index) + " (truncated file?)");
    const std::size_t bytes = static_cast<std::size_t>(want / page_ * page_);
    if (fd_ < 0) {
      block_ = whole_.data() + at;
    } else {
      buf_.resize(bytes);
      if (pread_full(fd_, buf_.data(), bytes, at) < bytes)
        fail(name_, "cannot read page " + std::to_string(index) + " (file shrank while read?)");
      block_ = buf_.data();
    }
    first_ = index;
    count_ = bytes / page_;
    for (std::uint64_t k = 0; k < count_; ++k) {
      const auto* p = reinterpret_cast<const unsigned char*>(block_ + k * page_);
      const std::uint32_t stored = std::uint32_t(p[page_ - 4]) << 24 | std::uint32_t(p[page_ - 3]) << 16 |
                                   std::uint32_t(p[page_ - 2]) << 8 | p[page_ - 1];
      if (e57_crc32c(p, page_ - 4) != stored)
        fail(name_, "page " + std::to_string(first_ + k) + " (bytes " + std::to_string((first_ + k) * page_) +
                        " to " + std::to_string((first_ + k + 1) * page_ - 1) +
                        ") fails its CRC-32C checksum (corrupt file?)");
    }
    return block_;
  }

  std::string name_;
  int fd_;
  std::uint64_t page_, size_ = 0;
  std::string_view whole_;
  std::vector<char> buf_;
  const char* block_ = nullptr;
  std::uint64_t first_ = 0, count_ = 0;
};

struct E57Header {
  std::uint64_t length = 0, xml_offset = 0, xml_length = 0, page = 0;
};

E57Header read_header(ByteSource& src) {
  const std::string& name = src.name();
  while (src.bytes().size() < 48 && src.fetch(48 - src.bytes().size()) > 0) {
  }
  const std::string_view b = src.bytes();
  if (b.size() < 8 || b.compare(0, 8, "ASTM-E57") != 0)
    fail(name, "file expected (it does not start with ASTM-E57)");
  if (b.size() < 48) fail(name, "header ends after " + std::to_string(b.size()) + " bytes (truncated file?)");
  const char* p = b.data();
  if (le<std::uint32_t>(p + 8) != 1)
    fail(name, "version " + std::to_string(le<std::uint32_t>(p + 8)) + "." +
                   std::to_string(le<std::uint32_t>(p + 12)) + " is not supported (1.x is)");
  E57Header h{le<std::uint64_t>(p + 16), le<std::uint64_t>(p + 24), le<std::uint64_t>(p + 32),
              le<std::uint64_t>(p + 40)};
  if (h.page < 64 || h.page > (1u << 20) || h.page % 4 != 0 || h.length % h.page != 0)
    fail(name, "header's page size " + std::to_string(h.page) + " or file length " +
                   std::to_string(h.length) + " is impossible (corrupt file?)");
  if (src.size() >= 0 && static_cast<std::uint64_t>(src.size()) < h.length)
    fail(name, "header declares " + std::to_string(h.length) + " bytes but the file holds only " +
                   std::to_string(src.size()) + " (truncated file?)");
  return h;
}

// One field's bytestream: the bytes of the packets read so far, less those decoded.
struct Stream {
  std::string bytes;
  std::uint64_t bit = 0;  // bits of `bytes` decoded
};

// A field that is read: its description, its bytestream, its scaled axis.
struct Reading {
  const E57Field* field;
  Stream stream;
  ScaledAxis axis;
  // Values ready to decode.
  std::uint64_t available() const {
    const std::uint64_t bits = stream.bytes.size() * 8 - stream.bit;
    if (field->kind == 'f') return bits / (field->single ? 32 : 64);
    return field->bits == 0 ? ~std::uint64_t(0) : bits / static_cast<unsigned>(field->bits);
  }
  // The next value.
  double next() {
    const char* p = stream.bytes.data() + stream.bit / 8;
    if (field->kind == 'f') {
      stream.bit += field->single ? 32 : 64;
      return field->single ? double(le<float>(p)) : le<double>(p);
    }
    std::uint64_t raw = 0;
    unsigned shift = stream.bit % 8;
    if (field->bits <= 56 && stream.bit / 8 + 8 <= stream.bytes.size())  // one load
      raw = (le<std::uint64_t>(p) >> shift) & ((std::uint64_t(1) << field->bits) - 1);
    else
      for (int got = 0; got < field->bits; ++p) {
        const int take = std::min(8 - static_cast<int>(shift), field->bits - got);
        raw |= std::uint64_t((static_cast<unsigned char>(*p) >> shift) & ((1u << take) - 1)) << got;
        got += take;
        shift = 0;
      }
    stream.bit += static_cast<unsigned>(field->bits);
    const auto v = static_cast<std::int64_t>(static_cast<std::uint64_t>(field->minimum) + raw);
    return field->kind == 's' ? axis(v) : static_cast<double>(v);
  }
  // Drops the decoded whole bytes.
  void compact() {
    stream.bytes.erase(0, stream.bit / 8);
    stream.bit %= 8;
  }
};

// The points of one scan.
class ScanReader {
public:
  ScanReader(Pages& pages, const E57Scan& scan, const std::string& name)
      : pages_(pages), scan_(scan), name_(name) {
    for (int c = 0; c < 3; ++c) want(scan.coord[c]);
    if (scan.invalid >= 0) want(scan.invalid);
  }
  void run(Chunker& out);

private:
  void want(int f) {
    slot_[static_cast<std::size_t>(f)] = static_cast<int>(read_.size());
    const E57Field& field = scan_.fields[static_cast<std::size_t>(f)];
    read_.push_back({&field, {}, ScaledAxis(field.scale, field.offset)});
  }
  Reading& of(int f) { return read_[static_cast<std::size_t>(slot_.at(static_cast<std::size_t>(f)))]; }
  void packet(const std::vector<char>& p, std::uint64_t at);
  void decode(Chunker& out);
  std::string where(std::uint64_t logical) const {
    return scan_.label + "'s data packet at byte " + std::to_string(pages_.physical(logical));
  }

  Pages& pages_;
  const E57Scan& scan_;
  const std::string& name_;
  std::vector<Reading> read_;
  std::vector<int> slot_ = std::vector<int>(scan_.fields.size(), -1);
  std::uint64_t done_ = 0;
};

void ScanReader::run(Chunker& out) {
  char head[32];
  const std::uint64_t start = pages_.logical(scan_.offset), end_of_file = pages_.logical(pages_.size());
  if (start + 32 > end_of_file) fail(name_, scan_.label + "'s points lie beyond the end of the file");
  pages_.read(start, 32, head);
  const std::uint64_t length = le<std::uint64_t>(head + 8);
  std::uint64_t at = pages_.logical(le<std::uint64_t>(head + 16));
  if (head[0] != 1 || length < 32 || length > end_of_file - start || at < start + 32 || at > start + length)
    fail(name_, scan_.label + "'s points section at byte " + std::to_string(scan_.offset) +
                    " has an impossible header (corrupt file?)");
  const std::uint64_t end = start + length;
  std::vector<char> p;
  while (done_ < scan_.records) {
    char h[4];
    if (at + 4 > end) break;
    pages_.read(at, 4, h);
    const std::uint64_t size = std::uint64_t(le<std::uint16_t>(h + 2)) + 1;
    if (at + size > end) fail(name_, where(at) + " runs past its section's end (corrupt file?)");
    if (h[0] == 1) {
      p.resize(size);
      pages_.read(at, size, p.data());
      packet(p, at);
      decode(out);
    } else if (h[0] != 0 && h[0] != 2) {
      fail(name_, where(at) + " is of unknown type " + std::to_string(static_cast<unsigned char>(h[0])) +
                      " (corrupt file?)");
    }
    at += size;
  }
  if (done_ < scan_.records)
    fail(name_, scan_.label + "'s points end after " + std::to_string(done_) + " of its " +
                    std::to_string(scan_.records) + " records (corrupt file?)");
}

// Appends a data packet's bytestreams to the fields read.
void ScanReader::packet(const std::vector<char>& p, std::uint64_t at) {
  if (p.size() < 6) fail(name_, where(at) + " is too short (corrupt file?)");
  const std::size_t count = le<std::uint16_t>(p.data() + 4);
  if (count != scan_.fields.size())
    fail(name_, where(at) + " holds " + std::to_string(count) + " bytestreams, its prototype " +
                    std::to_string(scan_.fields.size()) + " fields (corrupt file?)");
  std::size_t from = 6 + 2 * count;
  if (from > p.size()) fail(name_, where(at) + " is too short for its bytestreams (corrupt file?)");
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t n = le<std::uint16_t>(p.data() + 6 + 2 * k);
    if (from + n > p.size()) fail(name_, where(at) + "'s bytestreams run past its end (corrupt file?)");
    if (slot_[k] >= 0) read_[static_cast<std::size_t>(slot_[k])].stream.bytes.append(p.data() + from, n);
    from += n;
  }
}

// Decodes every record whose fields are all at hand.
void ScanReader::decode(Chunker& out) {
  std::uint64_t ready = scan_.records - done_;
  for (const Reading& r : read_) ready = std::min(ready, r.available());
  Reading& a = of(scan_.coord[0]);
  Reading& b = of(scan_.coord[1]);
  Reading& c = of(scan_.coord[2]);
  Reading* invalid = scan_.invalid >= 0 ? &of(scan_.invalid) : nullptr;
  for (std::uint64_t k = 0; k < ready; ++k) {
    const double u = a.next(), v = b.next(), w = c.next();
    if ((invalid && invalid->next() != 0) || std::isnan(u) || std::isnan(v) || std::isnan(w)) continue;
    Eigen::Vector3d q(u, v, w);
    if (scan_.spherical)  // range, azimuth, elevation (E2807, 8.4.4)
      q = Eigen::Vector3d(u * std::cos(w) * std::cos(v), u * std::cos(w) * std::sin(v), u * std::sin(w));
    if (!q.allFinite())
      fail(name_, scan_.label + "'s point " + std::to_string(done_ + k + 1) + " has an infinite coordinate");
    if (scan_.posed) q = scan_.rotation * q + scan_.translation;
    out.add(q.x(), q.y(), q.z());
  }
  done_ += ready;
  for (Reading& r : read_) {
    r.compact();
    if (r.stream.bytes.size() > (std::size_t(1) << 26))  // writers fill each packet with every field
      fail(name_, scan_.label + "'s bytestreams are out of step: 64 MiB of its field " + r.field->name +
                      " wait for the others (corrupt file?)");
  }
}

}  // namespace

std::uint32_t e57_crc32c(const unsigned char* p, std::size_t n) {
#ifdef SECTION_CRC32C_SSE42
  static const bool sse42 = __builtin_cpu_supports("sse4.2");
  if (sse42) return crc32c_sse42(p, n);
#endif
  return crc32c_table(p, n);
}

std::size_t read_e57_cloud(ByteSource& src, const CloudReadOptions& opt, const PointChunkFn& fn,
                           const PointChunkFn&) {
  const std::string& name = src.name();
  const E57Header h = read_header(src);
  Pages pages(src, h.page);
  if (h.xml_length == 0 || h.xml_length > max_input_bytes() ||
      pages.logical(h.xml_offset) + h.xml_length > pages.logical(h.length))
    fail(name, "header's XML section (" + std::to_string(h.xml_length) + " bytes at byte " +
                   std::to_string(h.xml_offset) + ") does not fit the file (corrupt file?)");
  std::string xml(static_cast<std::size_t>(h.xml_length), '\0');
  pages.read(pages.logical(h.xml_offset), xml.size(), xml.data());
  const std::vector<E57Scan> scans = e57_scans(xml, name);
  unsigned long long total = 0;
  for (const E57Scan& s : scans) total += s.records;
  if (total > opt.max_points)
    fail(name, "file declares " + std::to_string(total) + " points, more than the limit of " +
                   std::to_string(opt.max_points));
  Chunker out(fn, opt.chunk_points);
  for (const E57Scan& s : scans) ScanReader(pages, s, name).run(out);
  out.flush();
  if (out.total() == 0) fail(name, "file holds no valid points (" + std::to_string(total) + " records)");
  return out.total();
}

}  // namespace section::detail
