// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The entropy decoder of LAZ: LASzip's adaptive arithmetic decoder (Amir Said's FastAC as
// LASzip adapts it), its adaptive bit and symbol models and its integer decompressor, written
// again from LASzip's sources (arithmeticdecoder.cpp, arithmeticmodel.cpp,
// integercompressor.cpp; rapidlasso GmbH, Apache License 2.0): LAZ has no specification
// beside them. Decoding only; every model as LASzip initialises and updates it, so that the
// numbers come out bit for bit.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace section::detail::laz {

/// An adaptive model of one bit.
struct BitModel {
  std::uint32_t update_cycle = 4, until_update = 4, bit_0_prob = 1u << 12, bit_0_count = 1, bit_count = 2;
  void init() { *this = BitModel(); }
  void update();
};

/// An adaptive model of `symbols` symbols (2 to 2048).
struct Model {
  explicit Model(std::uint32_t symbols = 2) : symbols(symbols) { init(); }
  void init();
  void update();
  std::uint32_t symbols;
  std::vector<std::uint32_t> distribution, count;
  std::vector<std::uint32_t>
      table;  ///< more than 16 symbols: where to start the search, by the value's top bits
  std::uint32_t total = 0, update_cycle = 0, until_update = 0, table_shift = 0;
};

/// A streaming median of the last five values (LASzip's StreamingMedian5).
struct Median5 {
  std::int32_t v[5] = {0, 0, 0, 0, 0};
  bool high = true;
  void add(std::int32_t x);
  std::int32_t get() const { return v[2]; }
};

/// The arithmetic decoder over a byte source (`next_byte` throws at the end of the input).
class Decoder {
public:
  explicit Decoder(std::function<unsigned char()> next_byte) : next_(std::move(next_byte)) {}
  /// Starts a chunk: reads its first 4 bytes.
  void init();
  unsigned bit(BitModel& m);
  unsigned symbol(Model& m);
  /// `n` raw bits (1 to 32).
  std::uint32_t bits(unsigned n);
  std::uint32_t int32() {
    const std::uint32_t low = bits(16);
    return bits(16) << 16 | low;
  }

private:
  void renormalise();
  std::function<unsigned char()> next_;
  std::uint32_t value_ = 0, length_ = 0;
};

/// LASzip's IntegerCompressor, decompressing: an integer as its prediction plus a corrector
/// coded by its bit length k (per context) and then its bits.
class Integers {
public:
  explicit Integers(unsigned bits = 16, unsigned contexts = 1, unsigned bits_high = 8);
  /// Resets the models (at each chunk).
  void init();
  std::int32_t decompress(Decoder& d, std::int32_t prediction, unsigned context = 0);
  /// The bit length of the last corrector.
  unsigned k() const { return k_; }

private:
  std::int32_t corrector(Decoder& d, Model& bits);
  unsigned corr_bits_, bits_high_, k_ = 0;
  std::uint32_t corr_range_;
  std::int32_t corr_min_;
  std::vector<Model> k_models_;    // per context
  BitModel zero_;                  // k = 0
  std::vector<Model> correctors_;  // k = 1 .. corr_bits (index k - 1)
};

}  // namespace section::detail::laz

namespace section::detail::laz {

/// LASzip's layered point14 items (version 3: LAS 1.4 point formats 6-10), decoded for the
/// coordinates only (lasreaditemcompressed_v3.cpp): each chunk holds its first record raw,
/// then every field in its own arithmetic-coded layer; X and Y share a layer with the
/// scanner channel and the returns (their contexts), Z has its own. The other layers are
/// skipped.
class Point14Xyz {
public:
  Point14Xyz();
  ~Point14Xyz();
  /// Starts a chunk from its raw first record `raw` (30 bytes) and the bytes of its XY and
  /// Z layers (kept by the caller until the chunk is read).
  void init(const unsigned char* raw, const std::string& xy, const std::string& z);
  /// Decodes the next point's X, Y and Z.
  void next(std::int32_t xyz[3]);

private:
  struct Context;
  void start(unsigned channel, const Context& from);
  std::vector<Context> contexts_;
  unsigned current_ = 0;
  std::size_t xy_at_ = 0, z_at_ = 0;
  const std::string* xy_ = nullptr;
  const std::string* z_ = nullptr;
  Decoder xy_decoder_, z_decoder_;
};

}  // namespace section::detail::laz
