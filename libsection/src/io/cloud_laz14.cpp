// SPDX-License-Identifier: GPL-3.0-or-later
// LAZ's layered point14 coordinates (see cloud_laz_codec.h), written again from LASzip's
// lasreaditemcompressed_v3.cpp and laszip_common_v3.hpp (rapidlasso GmbH, Apache License
// 2.0): the contexts per scanner channel, the returns that choose the predictions' contexts,
// X and Y as differences predicted by the median of the last five, Z by the last of its
// return level.
#include "io/cloud_laz_codec.h"

#include "io/cloud_readers.h"
#include "section/error.h"

#include <array>
#include <memory>

namespace section::detail::laz {

namespace {

// laszip_common_v3.hpp: by number of returns n and return number r.
constexpr std::uint8_t return_map_6[16][16] = {
    {0, 1, 2, 3, 4, 5, 3, 4, 4, 5, 5, 5, 5, 5, 5, 5}, {1, 0, 1, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3},
    {2, 1, 2, 4, 4, 4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3}, {3, 3, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {3, 3, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {4, 3, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5}};

// |n - r| capped at 7 (number_return_level_8ctx).
unsigned return_level(unsigned n, unsigned r) {
  return std::min(n > r ? n - r : r - n, 7u);
}

// A 16-symbol model per last value, made when first needed.
struct Lazy16 {
  std::array<std::unique_ptr<Model>, 16> m;
  unsigned next(Decoder& d, unsigned last) {
    if (!m[last]) m[last] = std::make_unique<Model>(16);
    return d.symbol(*m[last]);
  }
};

}  // namespace

struct Point14Xyz::Context {
  bool unused = true;
  std::int32_t x = 0, y = 0, z = 0;
  unsigned r = 0, n = 0;    // return number, number of returns
  bool gps_change = false;  // of the last point
  std::vector<Model> changed = std::vector<Model>(8, Model(128));
  Model channel{3}, r_gps_same{13};
  Lazy16 n_models, r_models;
  Integers dx{32, 2}, dy{32, 22}, dz{32, 20};
  Median5 x_median[12], y_median[12];
  std::int32_t last_z[8] = {};
};

Point14Xyz::Point14Xyz()
    : contexts_(4),
      xy_decoder_([this]() -> unsigned char {
        if (xy_at_ >= xy_->size()) throw Error("LAZ: a point14 XY layer ends early");
        return static_cast<unsigned char>((*xy_)[xy_at_++]);
      }),
      z_decoder_([this]() -> unsigned char {
        if (z_at_ >= z_->size()) throw Error("LAZ: a point14 Z layer ends early");
        return static_cast<unsigned char>((*z_)[z_at_++]);
      }) {}

Point14Xyz::~Point14Xyz() = default;

// Context `channel` made anew from the last point of `from` (createAndInitModelsAndDecompressors).
void Point14Xyz::start(unsigned channel, const Context& from) {
  Context fresh;
  fresh.unused = false;
  fresh.x = from.x;
  fresh.y = from.y;
  fresh.z = from.z;
  fresh.r = from.r;
  fresh.n = from.n;
  fresh.gps_change = from.gps_change;
  for (Integers* ic : {&fresh.dx, &fresh.dy, &fresh.dz}) ic->init();
  std::fill(std::begin(fresh.last_z), std::end(fresh.last_z), from.z);
  contexts_[channel] = std::move(fresh);
}

void Point14Xyz::init(const unsigned char* raw, const std::string& xy, const std::string& z) {
  xy_ = &xy;
  z_ = &z;
  xy_at_ = z_at_ = 0;
  Context first;
  const char* p = reinterpret_cast<const char*>(raw);
  first.x = le<std::int32_t>(p);
  first.y = le<std::int32_t>(p + 4);
  first.z = le<std::int32_t>(p + 8);
  first.r = raw[14] & 15;
  first.n = raw[14] >> 4;
  for (Context& c : contexts_) c.unused = true;
  current_ = (raw[15] >> 4) & 3;
  start(current_, first);
  if (!xy.empty()) xy_decoder_.init();
  if (!z.empty()) z_decoder_.init();
}

void Point14Xyz::next(std::int32_t xyz[3]) {
  Context* c = &contexts_[current_];
  const unsigned lpr = (c->r == 1 ? 1u : 0u) + (c->r >= c->n ? 2u : 0u) + (c->gps_change ? 4u : 0u);
  Decoder& d = xy_decoder_;
  const unsigned changed = d.symbol(c->changed[lpr]);
  if (changed & 64) {  // another scanner channel: its context, made from this one's point if new
    const unsigned channel = (current_ + d.symbol(c->channel) + 1) % 4;
    if (contexts_[channel].unused) start(channel, *c);
    current_ = channel;
    c = &contexts_[current_];
  }
  const bool gps_change = (changed & 16) != 0;
  const unsigned last_n = c->n, last_r = c->r;
  const unsigned n = (changed & 4) ? c->n_models.next(d, last_n) : last_n;
  unsigned r = last_r;
  if ((changed & 3) == 1)
    r = (last_r + 1) % 16;
  else if ((changed & 3) == 2)
    r = (last_r + 15) % 16;
  else if ((changed & 3) == 3)
    r = gps_change ? c->r_models.next(d, last_r) : (last_r + d.symbol(c->r_gps_same) + 2) % 16;
  c->n = n;
  c->r = r;
  const unsigned m = return_map_6[n][r], l = return_level(n, r), slot = m << 1 | (gps_change ? 1 : 0);
  std::int32_t diff = c->dx.decompress(d, c->x_median[slot].get(), n == 1);
  c->x = static_cast<std::int32_t>(static_cast<std::uint32_t>(c->x) + static_cast<std::uint32_t>(diff));
  c->x_median[slot].add(diff);
  unsigned k = c->dx.k();
  diff = c->dy.decompress(d, c->y_median[slot].get(), (n == 1) + (k < 20 ? k & ~1u : 20));
  c->y = static_cast<std::int32_t>(static_cast<std::uint32_t>(c->y) + static_cast<std::uint32_t>(diff));
  c->y_median[slot].add(diff);
  if (!z_->empty()) {
    k = (c->dx.k() + c->dy.k()) / 2;
    c->z = c->dz.decompress(z_decoder_, c->last_z[l], (n == 1) + (k < 18 ? k & ~1u : 18));
    c->last_z[l] = c->z;
  }
  c->gps_change = gps_change;
  xyz[0] = c->x;
  xyz[1] = c->y;
  xyz[2] = c->z;
}

}  // namespace section::detail::laz
