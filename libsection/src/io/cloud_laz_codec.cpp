// SPDX-License-Identifier: GPL-3.0-or-later
// LAZ's arithmetic decoder, models and integer decompressor (see cloud_laz_codec.h): the
// constants and update rules are LASzip's, each step as it does it.
#include "io/cloud_laz_codec.h"

#include "section/error.h"

namespace section::detail::laz {

namespace {

constexpr std::uint32_t min_length = 0x01000000u;  // renormalise below this
constexpr std::uint32_t max_length = 0xFFFFFFFFu;
constexpr unsigned bit_shift = 13;  // BM__LengthShift
constexpr std::uint32_t bit_max_count = 1u << bit_shift;
constexpr unsigned symbol_shift = 15;  // DM__LengthShift
constexpr std::uint32_t symbol_max_count = 1u << symbol_shift;

}  // namespace

void BitModel::update() {
  if ((bit_count += update_cycle) > bit_max_count) {
    bit_count = (bit_count + 1) >> 1;
    bit_0_count = (bit_0_count + 1) >> 1;
    if (bit_0_count == bit_count) ++bit_count;
  }
  const std::uint32_t scale = 0x80000000u / bit_count;
  bit_0_prob = (bit_0_count * scale) >> (31 - bit_shift);
  update_cycle = (5 * update_cycle) >> 2;
  if (update_cycle > 64) update_cycle = 64;
  until_update = update_cycle;
}

void Model::init() {
  if (symbols < 2 || symbols > (1u << 11))
    throw Error("LAZ: a model of " + std::to_string(symbols) + " symbols");
  distribution.assign(symbols, 0);
  count.assign(symbols, 1);
  if (symbols > 16) {
    unsigned table_bits = 3;
    while (symbols > (1u << (table_bits + 2))) ++table_bits;
    table.assign((std::size_t(1) << table_bits) + 2, 0);
    table_shift = symbol_shift - table_bits;
  }
  total = 0;
  update_cycle = symbols;
  update();
  until_update = update_cycle = (symbols + 6) >> 1;
}

void Model::update() {
  if ((total += update_cycle) > symbol_max_count) {
    total = 0;
    for (std::uint32_t n = 0; n < symbols; ++n) total += (count[n] = (count[n] + 1) >> 1);
  }
  std::uint32_t sum = 0, s = 0;
  const std::uint32_t scale = 0x80000000u / total;
  for (std::uint32_t k = 0; k < symbols; ++k) {
    distribution[k] = (scale * sum) >> (31 - symbol_shift);
    sum += count[k];
    if (!table.empty())
      for (const std::uint32_t w = distribution[k] >> table_shift; s < w;) table[++s] = k - 1;
  }
  if (!table.empty()) {
    table[0] = 0;
    while (s + 1 < table.size()) table[++s] = symbols - 1;
  }
  update_cycle = (5 * update_cycle) >> 2;
  const std::uint32_t most = (symbols + 6) << 3;
  if (update_cycle > most) update_cycle = most;
  until_update = update_cycle;
}

void Median5::add(std::int32_t x) {
  if (high) {
    if (x < v[2]) {
      v[4] = v[3];
      v[3] = v[2];
      if (x < v[0]) {
        v[2] = v[1];
        v[1] = v[0];
        v[0] = x;
      } else if (x < v[1]) {
        v[2] = v[1];
        v[1] = x;
      } else {
        v[2] = x;
      }
    } else {
      if (x < v[3]) {
        v[4] = v[3];
        v[3] = x;
      } else {
        v[4] = x;
      }
      high = false;
    }
  } else {
    if (v[2] < x) {
      v[0] = v[1];
      v[1] = v[2];
      if (v[4] < x) {
        v[2] = v[3];
        v[3] = v[4];
        v[4] = x;
      } else if (v[3] < x) {
        v[2] = v[3];
        v[3] = x;
      } else {
        v[2] = x;
      }
    } else {
      if (v[1] < x) {
        v[0] = v[1];
        v[1] = x;
      } else {
        v[0] = x;
      }
      high = true;
    }
  }
}

void Decoder::init() {
  length_ = max_length;
  value_ = 0;
  for (int i = 0; i < 4; ++i) value_ = value_ << 8 | next_();
}

void Decoder::renormalise() {
  do value_ = value_ << 8 | next_();
  while ((length_ <<= 8) < min_length);
}

unsigned Decoder::bit(BitModel& m) {
  const std::uint32_t x = m.bit_0_prob * (length_ >> bit_shift);
  const unsigned sym = value_ >= x;
  if (sym == 0) {
    length_ = x;
    ++m.bit_0_count;
  } else {
    value_ -= x;
    length_ -= x;
  }
  if (length_ < min_length) renormalise();
  if (--m.until_update == 0) m.update();
  return sym;
}

// A symbol: by the model's table where it has one (then bisection between the table's
// bounds), else by multiplications and bisection, as LASzip decodes it.
unsigned Decoder::symbol(Model& m) {
  std::uint32_t x = 0, y = length_, sym = 0, n = m.symbols;
  if (!m.table.empty()) {
    const std::uint32_t dv = value_ / (length_ >>= symbol_shift);
    const std::uint32_t t = dv >> m.table_shift;
    if (t + 1 >= m.table.size()) throw Error("LAZ: corrupt arithmetic-coded data");
    sym = m.table[t];
    n = m.table[t + 1] + 1;
    while (n > sym + 1) {
      const std::uint32_t k = (sym + n) >> 1;
      if (m.distribution[k] > dv)
        n = k;
      else
        sym = k;
    }
    x = m.distribution[sym] * length_;
    if (sym != m.symbols - 1) y = m.distribution[sym + 1] * length_;
  } else {
    length_ >>= symbol_shift;
    std::uint32_t k = n >> 1;
    do {
      const std::uint32_t z = length_ * m.distribution[k];
      if (z > value_) {
        n = k;
        y = z;
      } else {
        sym = k;
        x = z;
      }
    } while ((k = (sym + n) >> 1) != sym);
  }
  value_ -= x;
  length_ = y - x;
  if (length_ < min_length) renormalise();
  ++m.count[sym];
  if (--m.until_update == 0) m.update();
  return sym;
}

std::uint32_t Decoder::bits(unsigned n) {
  if (n > 19) {
    const std::uint32_t low = bits(16);
    return bits(n - 16) << 16 | low;
  }
  const std::uint32_t sym = value_ / (length_ >>= n);
  value_ -= length_ * sym;
  if (length_ < min_length) renormalise();
  if (sym >= (1u << n)) throw Error("LAZ: corrupt arithmetic-coded data");
  return sym;
}

Integers::Integers(unsigned bits, unsigned contexts, unsigned bits_high)
    : corr_bits_(bits && bits < 32 ? bits : 32),
      bits_high_(bits_high),
      corr_range_(bits && bits < 32 ? 1u << bits : 0),
      corr_min_(bits && bits < 32 ? -static_cast<std::int32_t>(corr_range_ / 2) : INT32_MIN),
      k_models_(contexts, Model(corr_bits_ + 1)) {
  for (unsigned i = 1; i <= corr_bits_; ++i)
    correctors_.emplace_back(1u << (i <= bits_high_ ? i : bits_high_));
}

void Integers::init() {
  for (Model& m : k_models_) m.init();
  zero_.init();
  for (Model& m : correctors_) m.init();
}

std::int32_t Integers::decompress(Decoder& d, std::int32_t prediction, unsigned context) {
  std::int32_t real =
      static_cast<std::int32_t>(static_cast<std::uint32_t>(prediction) +
                                static_cast<std::uint32_t>(corrector(d, k_models_.at(context))));
  if (real < 0)
    real = static_cast<std::int32_t>(static_cast<std::uint32_t>(real) + corr_range_);
  else if (static_cast<std::uint32_t>(real) >= corr_range_ && corr_range_ != 0)
    real = static_cast<std::int32_t>(static_cast<std::uint32_t>(real) - corr_range_);
  return real;
}

std::int32_t Integers::corrector(Decoder& d, Model& bits) {
  k_ = d.symbol(bits);
  if (k_ == 0) return static_cast<std::int32_t>(d.bit(zero_));
  if (k_ >= 32) return corr_min_;
  std::int64_t c = d.symbol(correctors_[k_ - 1]);
  if (k_ > bits_high_) {
    const unsigned low = k_ - bits_high_;
    c = (c << low) | d.bits(low);
  }
  // c in [0, 2^k): the upper half stands for [2^(k-1) + 1, 2^k], the lower for [-(2^k - 1), -2^(k-1)]
  if (c >= (std::int64_t(1) << (k_ - 1)))
    c += 1;
  else
    c -= (std::int64_t(1) << k_) - 1;
  return static_cast<std::int32_t>(c);
}

}  // namespace section::detail::laz
