// SPDX-License-Identifier: GPL-3.0-or-later
// The LAZ reader: LASzip-compressed LAS, point formats 0-3 (items point10, gpstime11, rgb12
// and extra bytes, each of LASzip's version 2) and 6-8 (layered: point14, rgb14, rgbnir14
// and extra bytes, version 3; cloud_laz14.cpp decodes the coordinates' layers), written
// again from LASzip's sources (lasreadpoint.cpp, lasreaditemcompressed_v2.cpp and _v3.cpp,
// laszip_common_v2.hpp and _v3.hpp; rapidlasso GmbH, Apache License 2.0): LAZ has no
// specification beside them, and no LAZ library is a Debian 12 package. The LASzip VLR
// ("laszip encoded", 22204) lists the items of a record and the chunk size; the points
// follow in chunks (after the 8-byte offset of the chunk table when chunked), each its
// first point raw, then the others arithmetic-coded as differences from the point before:
// in one stream for every item (formats 0-3), or in one stream a field (layered, 6-8).
// Wave packets (formats 4, 5, 9, 10), item versions 1 and 4 and variable chunks are refused,
// saying how to decompress.
#include "io/cloud_laz.h"

#include "io/cloud_laz_codec.h"
#include "io/cloud_readers.h"
#include "section/error.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>

namespace section::detail {

namespace {

using laz::Decoder;
using laz::Integers;
using laz::Median5;
using laz::Model;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw Error("read_cloud: " + name + ": " + what);
}

std::string decompress_hint(const std::string& name) {
  return ": decompress it to LAS first (laszip -i " + name + " -o FILE.las; pdal translate " + name +
         " FILE.las; or Python's laspy with lazrs: laspy.read('" + name + "').write('FILE.las'))";
}

std::uint8_t fold(int n) {  // U8_FOLD
  return static_cast<std::uint8_t>(n < 0 ? n + 256 : n > 255 ? n - 256 : n);
}
int clamp(int n) {  // U8_CLAMP
  return n <= 0 ? 0 : n >= 255 ? 255 : n;
}

// One item of a record (LASzip's LASreadItemCompressed_*_v2): started from a chunk's raw
// first point, then decoding each next one into `item`.
struct Item {
  virtual ~Item() = default;
  virtual void init(const unsigned char* item) = 0;
  virtual void read(Decoder& d, unsigned char* item) = 0;
};

// laszip_common_v2.hpp: by number of returns n and return number r.
constexpr std::uint8_t return_map[8][8] = {{15, 14, 13, 12, 11, 10, 9, 8},  {14, 0, 1, 3, 6, 10, 10, 9},
                                           {13, 1, 2, 4, 7, 11, 11, 10},    {12, 3, 4, 5, 8, 12, 12, 11},
                                           {11, 6, 7, 8, 9, 13, 13, 12},    {10, 10, 11, 12, 13, 14, 14, 13},
                                           {9, 10, 11, 12, 13, 14, 15, 14}, {8, 9, 10, 11, 12, 13, 14, 15}};
constexpr std::uint8_t return_level[8][8] = {
    {0, 1, 2, 3, 4, 5, 6, 7}, {1, 0, 1, 2, 3, 4, 5, 6}, {2, 1, 0, 1, 2, 3, 4, 5}, {3, 2, 1, 0, 1, 2, 3, 4},
    {4, 3, 2, 1, 0, 1, 2, 3}, {5, 4, 3, 2, 1, 0, 1, 2}, {6, 5, 4, 3, 2, 1, 0, 1}, {7, 6, 5, 4, 3, 2, 1, 0}};

// A byte's model per the byte's last value, made when first needed (LASzip's lazy models).
struct ModelPer256 {
  std::array<std::unique_ptr<Model>, 256> m;
  void init() {
    for (auto& p : m)
      if (p) p->init();
  }
  std::uint8_t next(Decoder& d, std::uint8_t last) {
    if (!m[last]) m[last] = std::make_unique<Model>(256);
    return static_cast<std::uint8_t>(d.symbol(*m[last]));
  }
};

// point10 (20 bytes: x, y, z, intensity, flags, classification, scan angle, user data, source).
class Point10 : public Item {
public:
  void init(const unsigned char* item) override;
  void read(Decoder& d, unsigned char* item) override;

private:
  unsigned char last_[20] = {};
  Model changed_{64}, scan_angle_[2] = {Model(256), Model(256)};
  Integers intensity_{16, 4}, source_{16}, dx_{32, 2}, dy_{32, 22}, dz_{32, 20};
  ModelPer256 flags_, classification_, user_data_;
  Median5 x_median_[16], y_median_[16];
  std::uint16_t intensity_last_[16] = {};
  std::int32_t height_[8] = {};
};

void Point10::init(const unsigned char* item) {
  for (int i = 0; i < 16; ++i) x_median_[i] = y_median_[i] = Median5();
  std::fill(std::begin(intensity_last_), std::end(intensity_last_), 0);
  std::fill(std::begin(height_), std::end(height_), 0);
  changed_.init();
  scan_angle_[0].init();
  scan_angle_[1].init();
  for (Integers* ic : {&intensity_, &source_, &dx_, &dy_, &dz_}) ic->init();
  flags_.init();
  classification_.init();
  user_data_.init();
  std::copy(item, item + 20, last_);
  last_[12] = last_[13] = 0;  // intensity starts from 0
}

void Point10::read(Decoder& d, unsigned char* item) {
  const unsigned changed = d.symbol(changed_);
  if (changed & 32) last_[14] = flags_.next(d, last_[14]);
  const unsigned r = last_[14] & 7, n = (last_[14] >> 3) & 7, m = return_map[n][r], l = return_level[n][r];
  if (changed) {
    std::uint16_t intensity = intensity_last_[m];
    if (changed & 16)
      intensity_last_[m] = intensity =
          static_cast<std::uint16_t>(intensity_.decompress(d, intensity, std::min(m, 3u)));
    std::memcpy(last_ + 12, &intensity, 2);
    if (changed & 8) last_[15] = classification_.next(d, last_[15]);
    if (changed & 4) last_[16] = fold(int(d.symbol(scan_angle_[(last_[14] >> 6) & 1])) + last_[16]);
    if (changed & 2) last_[17] = user_data_.next(d, last_[17]);
    if (changed & 1) {
      const auto source = static_cast<std::uint16_t>(
          source_.decompress(d, le<std::uint16_t>(reinterpret_cast<const char*>(last_ + 18))));
      std::memcpy(last_ + 18, &source, 2);
    }
  }
  const auto field = [&](int k) { return le<std::int32_t>(reinterpret_cast<const char*>(last_ + 4 * k)); };
  const auto set = [&](int k, std::int32_t v) { std::memcpy(last_ + 4 * k, &v, 4); };
  std::int32_t diff = dx_.decompress(d, x_median_[m].get(), n == 1);
  set(0, static_cast<std::int32_t>(static_cast<std::uint32_t>(field(0)) + static_cast<std::uint32_t>(diff)));
  x_median_[m].add(diff);
  unsigned k = dx_.k();
  diff = dy_.decompress(d, y_median_[m].get(), (n == 1) + (k < 20 ? k & ~1u : 20));
  set(1, static_cast<std::int32_t>(static_cast<std::uint32_t>(field(1)) + static_cast<std::uint32_t>(diff)));
  y_median_[m].add(diff);
  k = (dx_.k() + dy_.k()) / 2;
  set(2, dz_.decompress(d, height_[l], (n == 1) + (k < 18 ? k & ~1u : 18)));
  height_[l] = field(2);
  std::copy(last_, last_ + 20, item);
}

// t + d wrapping around, as LASzip's 64-bit sums do (a corrupt file's may overflow).
void add(std::int64_t& t, std::int64_t d) {
  t = static_cast<std::int64_t>(static_cast<std::uint64_t>(t) + static_cast<std::uint64_t>(d));
}

// gpstime11 (a double, coded as its 64 bits' integer differences in up to 4 sequences).
class GpsTime : public Item {
public:
  void init(const unsigned char* item) override;
  void read(Decoder& d, unsigned char* item) override;

private:
  static constexpr int multi_max = 500, multi_minus = -10, unchanged = multi_max - multi_minus + 1,
                       code_full = multi_max - multi_minus + 2, total = multi_max - multi_minus + 6;
  void full(Decoder& d);
  std::int32_t extreme(std::int32_t diff);
  Model multi_{total}, zero_diff_{6};
  Integers ic_{32, 9};
  unsigned last_ = 0, next_ = 0;
  std::int64_t time_[4] = {};
  std::int32_t diff_[4] = {};
  int extreme_[4] = {};
};

void GpsTime::init(const unsigned char* item) {
  last_ = next_ = 0;
  std::fill(std::begin(diff_), std::end(diff_), 0);
  std::fill(std::begin(extreme_), std::end(extreme_), 0);
  multi_.init();
  zero_diff_.init();
  ic_.init();
  time_[0] = le<std::int64_t>(reinterpret_cast<const char*>(item));
  time_[1] = time_[2] = time_[3] = 0;
}

// A new sequence from a time coded whole (its upper 32 bits predicted from the last).
void GpsTime::full(Decoder& d) {
  next_ = (next_ + 1) & 3;
  const auto high = static_cast<std::uint32_t>(
      ic_.decompress(d, static_cast<std::int32_t>(static_cast<std::uint64_t>(time_[last_]) >> 32), 8));
  time_[next_] = static_cast<std::int64_t>(std::uint64_t(high) << 32 | d.int32());
  last_ = next_;
  diff_[last_] = 0;
  extreme_[last_] = 0;
}

// A difference far from the expected one: after three in a row it becomes the expected one.
std::int32_t GpsTime::extreme(std::int32_t diff) {
  if (++extreme_[last_] > 3) {
    diff_[last_] = diff;
    extreme_[last_] = 0;
  }
  return diff;
}

void GpsTime::read(Decoder& d, unsigned char* item) {
  for (int switches = 0;; ++switches) {  // LASzip recurses on a switch of sequence
    if (switches > 4) throw Error("LAZ: corrupt gps time");
    if (diff_[last_] == 0) {
      const int multi = static_cast<int>(d.symbol(zero_diff_));
      if (multi == 1) {
        diff_[last_] = ic_.decompress(d, 0, 0);
        add(time_[last_], diff_[last_]);
        extreme_[last_] = 0;
      } else if (multi == 2) {
        full(d);
      } else if (multi > 2) {
        last_ = (last_ + static_cast<unsigned>(multi) - 2) & 3;
        continue;
      }
      break;
    }
    int multi = static_cast<int>(d.symbol(multi_));
    if (multi == 1) {
      add(time_[last_], ic_.decompress(d, diff_[last_], 1));
      extreme_[last_] = 0;
    } else if (multi < unchanged) {
      std::int32_t diff;
      const std::int32_t last = diff_[last_];
      if (multi == 0)
        diff = extreme(ic_.decompress(d, 0, 7));
      else if (multi < multi_max)
        diff = ic_.decompress(
            d,
            static_cast<std::int32_t>(static_cast<std::uint32_t>(multi) * static_cast<std::uint32_t>(last)),
            multi < 10 ? 2 : 3);
      else if (multi == multi_max)
        diff = extreme(ic_.decompress(d,
                                      static_cast<std::int32_t>(static_cast<std::uint32_t>(multi_max) *
                                                                static_cast<std::uint32_t>(last)),
                                      4));
      else if ((multi = multi_max - multi) > multi_minus)
        diff = ic_.decompress(
            d,
            static_cast<std::int32_t>(static_cast<std::uint32_t>(multi) * static_cast<std::uint32_t>(last)),
            5);
      else
        diff = extreme(ic_.decompress(d,
                                      static_cast<std::int32_t>(static_cast<std::uint32_t>(multi_minus) *
                                                                static_cast<std::uint32_t>(last)),
                                      6));
      add(time_[last_], diff);
    } else if (multi == code_full) {
      full(d);
    } else if (multi > code_full) {
      last_ = (last_ + static_cast<unsigned>(multi - code_full)) & 3;
      continue;
    }
    break;
  }
  std::memcpy(item, &time_[last_], 8);
}

// rgb12 (three 16-bit values, each byte coded as a difference, green and blue predicted from red).
class Rgb : public Item {
public:
  void init(const unsigned char* item) override {
    used_.init();
    for (Model& m : models_) m.init();
    for (int i = 0; i < 3; ++i) last_[i] = le<std::uint16_t>(reinterpret_cast<const char*>(item + 2 * i));
  }
  void read(Decoder& d, unsigned char* item) override;

private:
  Model used_{128};
  std::array<Model, 6> models_{Model(256), Model(256), Model(256), Model(256), Model(256), Model(256)};
  std::uint16_t last_[3] = {};
};

void Rgb::read(Decoder& d, unsigned char* item) {
  const unsigned sym = d.symbol(used_);
  const auto byte = [&](int k, int base) { return int(fold(int(d.symbol(models_[k])) + base)); };
  std::uint16_t c[3];
  c[0] = static_cast<std::uint16_t>(sym & 1 ? byte(0, last_[0] & 255) : last_[0] & 0xFF);
  c[0] |= static_cast<std::uint16_t>(sym & 2 ? byte(1, last_[0] >> 8) << 8 : last_[0] & 0xFF00);
  if (sym & 64) {
    int diff = (c[0] & 0xFF) - (last_[0] & 0xFF);
    c[1] = static_cast<std::uint16_t>(sym & 4 ? byte(2, clamp(diff + (last_[1] & 255))) : last_[1] & 0xFF);
    if (sym & 16) {
      diff = (diff + ((c[1] & 0xFF) - (last_[1] & 0xFF))) / 2;
      c[2] = static_cast<std::uint16_t>(byte(4, clamp(diff + (last_[2] & 255))));
    } else {
      c[2] = last_[2] & 0xFF;
    }
    diff = (c[0] >> 8) - (last_[0] >> 8);
    c[1] |=
        static_cast<std::uint16_t>(sym & 8 ? byte(3, clamp(diff + (last_[1] >> 8))) << 8 : last_[1] & 0xFF00);
    if (sym & 32) {
      diff = (diff + ((c[1] >> 8) - (last_[1] >> 8))) / 2;
      c[2] |= static_cast<std::uint16_t>(byte(5, clamp(diff + (last_[2] >> 8))) << 8);
    } else {
      c[2] |= last_[2] & 0xFF00;
    }
  } else {
    c[1] = c[2] = c[0];
  }
  std::copy(c, c + 3, last_);
  std::memcpy(item, c, 6);
}

// Extra bytes (byte items): each byte coded as a difference from its last value.
class Bytes : public Item {
public:
  explicit Bytes(std::size_t n) : models_(n, Model(256)), last_(n) {}
  void init(const unsigned char* item) override {
    for (Model& m : models_) m.init();
    std::copy(item, item + last_.size(), last_.begin());
  }
  void read(Decoder& d, unsigned char* item) override {
    for (std::size_t i = 0; i < last_.size(); ++i)
      item[i] = last_[i] = fold(last_[i] + int(d.symbol(models_[i])));
  }

private:
  std::vector<Model> models_;
  std::vector<unsigned char> last_;
};

// What the LASzip VLR says.
struct LazVlr {
  unsigned compressor = 0;                     // 1 pointwise, 2 pointwise chunked, 3 layered chunked
  std::uint32_t chunk = 0;                     // points a chunk (0xFFFFFFFF: variable)
  std::vector<std::array<unsigned, 3>> items;  // type, size, version
};

// The bytes from the start of the file to the points, consumed from `src`.
std::string head_bytes(ByteSource& src, const LasHeader& h) {
  std::string head;
  while (head.size() < h.data_offset) {
    if (src.bytes().empty() && src.fetch(block_size) == 0)
      fail(src.name(), "LAZ file ends before its points");
    const std::size_t n = std::min<std::size_t>(h.data_offset - head.size(), src.bytes().size());
    head.append(src.bytes().data(), n);
    src.consume(n);
  }
  return head;
}

LazVlr laszip_vlr(const std::string& head, const LasHeader& h, const std::string& name) {
  const auto count = le<std::uint32_t>(head.data() + 100);
  std::size_t at = h.header_size;
  for (std::uint32_t v = 0; v < count && at + 54 <= head.size(); ++v) {
    const std::string user(head.data() + at + 2, strnlen(head.data() + at + 2, 16));
    const auto id = le<std::uint16_t>(head.data() + at + 18);
    const std::size_t length = le<std::uint16_t>(head.data() + at + 20);
    const char* d = head.data() + at + 54;
    if (at + 54 + length > head.size()) break;
    if (user == "laszip encoded" && id == 22204 && length >= 34) {
      LazVlr z;
      z.compressor = le<std::uint16_t>(d);
      if (le<std::uint16_t>(d + 2) != 0)
        fail(name, "LAZ coder " + std::to_string(le<std::uint16_t>(d + 2)) + " is unknown");
      z.chunk = le<std::uint32_t>(d + 12);
      const unsigned items = le<std::uint16_t>(d + 32);
      if (34 + 6 * std::size_t(items) > length) break;
      for (unsigned i = 0; i < items; ++i)
        z.items.push_back({le<std::uint16_t>(d + 34 + 6 * i), le<std::uint16_t>(d + 36 + 6 * i),
                           le<std::uint16_t>(d + 38 + 6 * i)});
      return z;
    }
    at += 54 + length;
  }
  fail(name, "LAZ file without its LASzip VLR (corrupt file?)");
}

// The layers of each item of a layered (LAS 1.4) record, checked: point14 first, then
// rgb14, rgbnir14 or byte14 (a layer a byte), each of LASzip's version 3 (wave packets are
// refused).
std::vector<unsigned> layered_items(const LazVlr& z, const LasHeader& h, const std::string& name) {
  const std::string why = decompress_hint(name);
  std::vector<unsigned> layers;
  std::size_t record = 0;
  for (const auto& [type, size, version] : z.items) {
    static constexpr unsigned sizes[5] = {30, 6, 8, 29, 0};  // types 10-14
    if (type < 10 || type > 14 || (type != 14 && size != sizes[type - 10]) || size == 0)
      fail(name, "LAZ item " + std::to_string(type) + " of " + std::to_string(size) +
                     " bytes in layered compression (corrupt file?)");
    if (type == 13) fail(name, "LAZ of wave packets (point formats 9, 10) is not supported" + why);
    if (version != 3)
      fail(name, "LAZ layered item version " + std::to_string(version) + " is not supported (3 is)" + why);
    layers.push_back(type == 10 ? 9 : type == 12 ? 2 : type == 14 ? size : 1);
    record += size;
  }
  if (z.items.empty() || z.items[0][0] != 10 || record != h.record)
    fail(name,
         "LAZ items do not make its " + std::to_string(h.record) + "-byte point records (corrupt file?)");
  return layers;
}

// The item readers of a record, checked against what is read here.
std::vector<std::unique_ptr<Item>> item_readers(const LazVlr& z, const LasHeader& h,
                                                const std::string& name) {
  const std::string why = decompress_hint(name);
  if (h.format > 5 && z.compressor != 3)
    fail(name,
         "LAZ of point format " + std::to_string(h.format) + " without layered compression (corrupt file?)");
  if (z.compressor != 1 && z.compressor != 2 && z.compressor != 3)
    fail(name, "LAZ compressor " + std::to_string(z.compressor) + " is unknown" + why);
  if (z.compressor >= 2 && (z.chunk == 0 || z.chunk == 0xFFFFFFFFu))
    fail(name, "LAZ with variable chunks is not supported" + why);
  if (z.compressor == 3) return {};  // layered_items' items
  std::vector<std::unique_ptr<Item>> out;
  std::size_t record = 0;
  for (const auto& [type, size, version] : z.items) {
    static constexpr unsigned sizes[9] = {0, 0, 0, 0, 0, 0, 20, 8, 6};
    if (type == 9 || type > 9)
      fail(name,
           "LAZ item " + std::to_string(type) + " (wave packets or LAS 1.4 items) is not supported" + why);
    if (version != 2)
      fail(name, "LAZ item version " + std::to_string(version) + " is not supported (2 is)" + why);
    if (type < 6 ? size == 0 : size != sizes[type])
      fail(name,
           "LAZ item " + std::to_string(type) + " of " + std::to_string(size) + " bytes (corrupt file?)");
    if (type == 6)
      out.push_back(std::make_unique<Point10>());
    else if (type == 7)
      out.push_back(std::make_unique<GpsTime>());
    else if (type == 8)
      out.push_back(std::make_unique<Rgb>());
    else
      out.push_back(std::make_unique<Bytes>(size));
    record += size;
  }
  if (z.items.empty() || z.items[0][0] != 6 || record != h.record)
    fail(name,
         "LAZ items do not make its " + std::to_string(h.record) + "-byte point records (corrupt file?)");
  return out;
}

// When the chunk table is where its offset says, it must count the chunks the header's points
// make: a cheap check that the point count is not a corrupt one, to be decoded from garbage.
void check_chunk_table(ByteSource& src, std::int64_t at, std::uint64_t chunks) {
  if (at <= 0 || src.size() < 0 || at + 8 > src.size())
    return;  // no table (a writer that could not seek back)
  char table[8];
  if (src.regular_fd() >= 0) {
    if (pread_full(src.regular_fd(), table, 8, static_cast<unsigned long long>(at)) < 8) return;
  } else {
    const auto from = static_cast<long long>(src.offset());  // a source in memory: its bytes are at hand
    if (at < from || at + 8 > from + static_cast<long long>(src.bytes().size())) return;
    std::memcpy(table, src.bytes().data() + (at - from), 8);
  }
  const auto declared = le<std::uint32_t>(table + 4);
  if (le<std::uint32_t>(table) == 0 && declared != chunks)
    fail(src.name(), "LAZ chunk table lists " + std::to_string(declared) +
                         " chunks, its header's points make " + std::to_string(chunks) + " (corrupt file?)");
}

// The points of a layered LAZ file, chunk by chunk: the first record raw, the chunk's point
// count, every item's layer sizes, then the layers (point14's XY and Z kept, the rest skipped).
void read_layered(const std::function<unsigned char()>& byte, const LasHeader& h, const LazVlr& z,
                  const std::vector<unsigned>& layers, const std::function<void(const std::int32_t*)>& emit) {
  laz::Point14Xyz points;
  std::vector<unsigned char> record(h.record);
  std::string xy, zs;
  const auto u32 = [&] {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t(byte()) << (8 * i);
    return v;
  };
  for (std::uint64_t done = 0; done < h.count;) {
    const std::uint64_t want = std::min<std::uint64_t>(z.chunk, h.count - done);
    for (unsigned char& b : record) b = byte();
    if (u32() != want) throw Error("LAZ: a chunk's point count is not its header's");
    std::vector<std::uint32_t> sizes;
    for (const unsigned n : layers)
      for (unsigned i = 0; i < n; ++i) sizes.push_back(u32());
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      std::string* keep = i == 0 ? &xy : i == 1 ? &zs : nullptr;
      if (keep) keep->assign(sizes[i], '\0');
      for (std::uint32_t k = 0; k < sizes[i]; ++k) {
        const unsigned char b = byte();
        if (keep) (*keep)[k] = static_cast<char>(b);
      }
    }
    points.init(record.data(), xy, zs);
    const char* p = reinterpret_cast<const char*>(record.data());
    std::int32_t xyz[3] = {le<std::int32_t>(p), le<std::int32_t>(p + 4), le<std::int32_t>(p + 8)};
    emit(xyz);
    for (std::uint64_t i = 1; i < want; ++i) {
      points.next(xyz);
      emit(xyz);
    }
    done += want;
  }
}

}  // namespace

std::size_t read_laz_points(ByteSource& src, const LasHeader& h, const CloudReadOptions& opt,
                            const PointChunkFn& fn) {
  const std::string& name = src.name();
  const std::string head = head_bytes(src, h);
  const LazVlr z = laszip_vlr(head, h, name);
  std::vector<std::unique_ptr<Item>> items = item_readers(z, h, name);
  const std::vector<unsigned> layers =
      z.compressor == 3 ? layered_items(z, h, name) : std::vector<unsigned>();
  const auto byte = [&]() -> unsigned char {
    if (src.bytes().empty() && src.fetch(block_size) == 0)
      fail(name, "LAZ file ends inside its points (truncated file?)");
    const auto b = static_cast<unsigned char>(src.bytes()[0]);
    src.consume(1);
    return b;
  };
  const std::uint64_t chunk = z.compressor >= 2 ? z.chunk : h.count;
  if (z.compressor >= 2) {  // the chunk table's offset: the chunks are read in order, without it
    char offset[8];
    for (char& c : offset) c = static_cast<char>(byte());
    check_chunk_table(src, le<std::int64_t>(offset), (h.count + chunk - 1) / chunk);
  }
  Decoder d(byte);
  Chunker out(fn, opt.chunk_points);
  const ScaledAxis axis[3] = {
      {h.scale[0], h.offset[0]}, {h.scale[1], h.offset[1]}, {h.scale[2], h.offset[2]}};
  std::vector<unsigned char> record(h.record);
  try {
    if (z.compressor == 3)
      read_layered(byte, h, z, layers,
                   [&](const std::int32_t* q) { out.add(axis[0](q[0]), axis[1](q[1]), axis[2](q[2])); });
    for (std::uint64_t done = 0; z.compressor != 3 && done < h.count; ++done) {
      unsigned char* at = record.data();
      if (done % chunk == 0) {
        for (unsigned char& b : record) b = byte();
        for (std::size_t i = 0; i < items.size(); at += z.items[i][1], ++i) items[i]->init(at);
        d.init();
      } else {
        for (std::size_t i = 0; i < items.size(); at += z.items[i][1], ++i) items[i]->read(d, at);
      }
      const char* p = reinterpret_cast<const char*>(record.data());
      out.add(axis[0](le<std::int32_t>(p)), axis[1](le<std::int32_t>(p + 4)),
              axis[2](le<std::int32_t>(p + 8)));
    }
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind("LAZ: ", 0) == 0) fail(name, what + " (corrupt file?)");
    throw;
  }
  out.flush();
  return out.total();
}

}  // namespace section::detail
