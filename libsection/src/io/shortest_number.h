// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The stream's numbers written as std::to_chars(double) writes them (shortest round trip,
// fixed or scientific, whichever is shorter, fixed on a tie), without it for the magnitudes
// a stream holds: libstdc++'s to_chars took about 500 instructions a number, the largest
// part of writing a stream. The shortest digits are found with exact 128-bit integers (no
// tables of powers to trust): every decimal in the interval of reals that read back as the
// double is known, and the shortest, closest one is taken.
#include <cstdint>
#include <cstring>

namespace section::detail {

#if defined(__SIZEOF_INT128__)

/// 10^k as a 128-bit integer, k in [0, 24].
inline unsigned __int128 power_of_ten_128(int k) {
  struct Table {
    unsigned __int128 p[25];
    constexpr Table() : p() {
      p[0] = 1;
      for (int i = 1; i < 25; ++i) p[i] = p[i - 1] * 10;
    }
  };
  static constexpr Table table;
  return table.p[k];
}

/// The 8 decimal digits of `x` < 10^8 (leading zeros too) at `out`: split in lanes of four,
/// two and one digit, each lane divided by a multiplication (exact for these ranges).
inline void eight_digit_text(char* out, std::uint32_t x) {
  const std::uint64_t four = std::uint64_t(x / 10000) | (std::uint64_t(x % 10000) << 32);
  const std::uint64_t high2 = ((four * 10486) >> 20) & 0x0000007F0000007F;  // lane / 100
  const std::uint64_t two = high2 | ((four - high2 * 100) << 16);
  const std::uint64_t high1 = ((two * 103) >> 10) & 0x000F000F000F000F;  // lane / 10
  const std::uint64_t one = high1 | ((two - high1 * 10) << 8);
  const std::uint64_t text = one + 0x3030303030303030;  // the first digit in the lowest byte
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  for (int i = 0; i < 8; ++i) out[i] = char(text >> (8 * i));
#else
  std::memcpy(out, &text, 8);
#endif
}

/// The number of decimal digits of `x` > 0.
inline int decimal_length(std::uint64_t x) {
  static constexpr std::uint64_t tens[] = {1,
                                           10,
                                           100,
                                           1000,
                                           10000,
                                           100000,
                                           1000000,
                                           10000000,
                                           100000000,
                                           1000000000,
                                           10000000000,
                                           100000000000,
                                           1000000000000,
                                           10000000000000,
                                           100000000000000,
                                           1000000000000000,
                                           10000000000000000,
                                           100000000000000000,
                                           1000000000000000000,
                                           10000000000000000000u};
  const int bits = 64 - __builtin_clzll(x);
  const int t = (bits * 1233) >> 12;  // floor(log10(2^bits)): x < 10^(t+1)
  return t + (x >= tens[t]);
}

/// The shortest decimal that reads back as m 2^(e2-52) (2^52 < m < 2^53, e2 in [-17, 48]) and,
/// of those, the closest: `digits` 10^`exponent`. False where the closest is a tie.
inline bool shortest_decimal(std::uint64_t m, int e2, std::uint64_t& digits, int& exponent) {
  using u128 = unsigned __int128;
  const int s = 52 - e2;              // |v| = m / 2^s, s in [4, 69]
  const int e10 = (e2 * 1233) >> 12;  // floor(e2 log10(2)): 10^e10 <= |v| < 10^(e10 + 2)
  const int k = 16 - e10;             // |v| 10^k in [10^16, 10^18), k in [2, 22]
  const u128 ten_k = power_of_ten_128(k);
  const u128 n = u128(m) * ten_k;  // |v| 10^k = n / 2^s exactly (n < 2^127)
  // The reals that read back as v, times 10^k 2^(s+1): within 10^k of 2n (half a unit in
  // the last place either side), the ends included when m is even (ties go to even).
  const int shift = s + 1;
  const bool even = (m & 1) == 0;
  const u128 lower = 2 * n - ten_k, upper = 2 * n + ten_k;
  // The integers D with D 2^(s+1) in that interval: the decimals of 16 to 18 digits at
  // scale 10^-k that read back as v.
  std::uint64_t lo =
      even ? std::uint64_t((lower + ((u128(1) << shift) - 1)) >> shift) : std::uint64_t(lower >> shift) + 1;
  std::uint64_t hi = even ? std::uint64_t(upper >> shift) : std::uint64_t((upper - 1) >> shift);
  // Fewer digits while some decimal with them is still in the interval.
  int j = 0;
  std::uint64_t scale = 1;  // 10^j
  while (true) {
    const std::uint64_t next_lo = (lo + 9) / 10, next_hi = hi / 10;
    if (next_lo > next_hi) break;
    lo = next_lo;
    hi = next_hi;
    ++j;
    scale *= 10;
  }
  // Of those, the closest to |v|: |v| 10^(k-j) rounded (the interval is symmetric about it).
  const std::uint64_t whole = std::uint64_t(n >> s);  // |v| 10^k, truncated
  const u128 rest = n & ((u128(1) << s) - 1);         // and what it left, in units of 2^-s
  digits = whole / scale;
  const std::uint64_t r = whole % scale;
  bool up, tie;
  if (j == 0) {
    const u128 half = u128(1) << (s - 1);
    up = rest > half;
    tie = rest == half;
  } else {
    const std::uint64_t half = scale / 2;
    up = r > half || (r == half && rest != 0);
    tie = r == half && rest == 0;
  }
  digits += up;
  exponent = j - k;
  return !tie && digits >= lo && digits <= hi;  // (the last two cannot fail)
}

/// Writes `digits` 10^`exponent` (digits < 10^17, no trailing zero) as to_chars does: fixed
/// or scientific, whichever is shorter, fixed on a tie.
inline char* write_decimal(char* p, std::uint64_t digits, int exponent) {
  char buf[24];
  eight_digit_text(buf, std::uint32_t(digits / 10000000000000000));
  eight_digit_text(buf + 8, std::uint32_t(digits / 100000000 % 100000000));
  eight_digit_text(buf + 16, std::uint32_t(digits % 100000000));
  const int count = decimal_length(digits);
  const char* const first = buf + 24 - count;
  const int exp10 = count - 1 + exponent;          // d.ddd 10^exp10
  const int scientific = count + (count > 1) + 4;  // e+XX (|exp10| < 100 here)
  const int fixed = exp10 >= 0 ? (count <= exp10 + 1 ? exp10 + 1 : count + 1) : 1 - exp10 + count;
  if (fixed <= scientific) {
    if (exp10 < 0) {
      *p++ = '0';
      *p++ = '.';
      for (int z = -exp10 - 1; z > 0; --z) *p++ = '0';
      std::memcpy(p, first, std::size_t(count));
      return p + count;
    }
    if (count <= exp10 + 1) {
      std::memcpy(p, first, std::size_t(count));
      p += count;
      for (int z = exp10 + 1 - count; z > 0; --z) *p++ = '0';
      return p;
    }
    std::memcpy(p, first, std::size_t(exp10 + 1));
    p += exp10 + 1;
    *p++ = '.';
    std::memcpy(p, first + exp10 + 1, std::size_t(count - exp10 - 1));
    return p + count - exp10 - 1;
  }
  *p++ = first[0];
  if (count > 1) {
    *p++ = '.';
    std::memcpy(p, first + 1, std::size_t(count - 1));
    p += count - 1;
  }
  *p++ = 'e';
  *p++ = exp10 < 0 ? '-' : '+';
  const int e = exp10 < 0 ? -exp10 : exp10;  // (at most 14 here)
  *p++ = char('0' + e / 10);
  *p++ = char('0' + e % 10);
  return p;
}

/// Writes `v` as std::to_chars(p, p + 32, v) does and returns the end, for 2^-17 <= |v| <
/// 2^49 (7.6e-6 to 5.6e14) other than powers of two; nullptr (nothing written) for any
/// other value, or where the closest shortest decimal is a tie (left to to_chars).
inline char* shortest_number(char* p, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  const int e2 = int((bits >> 52) & 0x7FF) - 1023;  // 2^e2 <= |v| < 2^(e2 + 1)
  const std::uint64_t fraction = bits & ((std::uint64_t(1) << 52) - 1);
  // (A power of two has a narrower interval below it than above: not handled here.)
  if (e2 < -17 || e2 > 48 || fraction == 0) return nullptr;
  std::uint64_t digits;
  int exponent;
  // (At most 17 digits: with 18 the interval would hold a multiple of 10.)
  if (!shortest_decimal(fraction | (std::uint64_t(1) << 52), e2, digits, exponent) ||
      digits >= 100000000000000000)
    return nullptr;
  if (bits >> 63) *p++ = '-';
  return write_decimal(p, digits, exponent);
}

#else

inline char* shortest_number(char*, double) {
  return nullptr;
}

#endif

}  // namespace section::detail
