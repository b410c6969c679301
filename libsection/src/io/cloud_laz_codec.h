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
