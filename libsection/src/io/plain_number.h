// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The numbers of the stream in the form its writers give them (`-?D+(.D+)?`), read without
// std::from_chars where the result is provably the same double: half of a stage's time in
// reading a stream went to from_chars. A fraction's digits (most of a stream's bytes) are
// summed 16 at a time with SSE2 where it is there (x86-64), else 8 at a time.
#include <array>
#include <cfloat>
#include <cstdint>
#include <cstring>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace section::detail {

/// 10^0 to 10^16.
inline constexpr std::array<std::uint64_t, 17> ten_to = [] {
  std::array<std::uint64_t, 17> t{};
  std::uint64_t power = 1;
  for (auto& p : t) {
    p = power;
    power *= 10;
  }
  return t;
}();

#if defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
/// The value of eight digit characters read as a little-endian word (fast_float's SWAR sum).
inline std::uint64_t eight_digits(std::uint64_t x) {
  x -= 0x3030303030303030;
  x = (x * 10) + (x >> 8);
  return (((x & 0x000000FF000000FF) * (100 + (1000000ULL << 32))) +
          (((x >> 16) & 0x000000FF000000FF) * (1 + (10000ULL << 32)))) >>
         32;
}

/// The high bit of each byte of `x` that is not a digit; exact up to the first such byte
/// (no carry or borrow reaches it from the digits before), which is all that is used.
inline std::uint64_t non_digits(std::uint64_t x) {
  return ((x + 0x4646464646464646) | (x - 0x3030303030303030)) & 0x8080808080808080;
}

/// The value of the `n` (1 to 7) digits that lead `x`.
inline std::uint64_t leading_digits(std::uint64_t x, int n) {
  return eight_digits((x << (8 * (8 - n))) | (0x3030303030303030 >> (8 * n)));  // '0's before them
}
#endif

#ifdef __SSE2__
/// The value of the first `n` (1 to 16) of the 16 digit characters that end at `last`
/// (`last - 16` up to `last` readable; the bytes before the `n` digits are masked off): one
/// load and a few vector multiply-adds, pairs of digits, then fours, then eights.
inline std::uint64_t sixteen_digits_ending(const char* last, int n) {
  alignas(16) static constexpr unsigned char keep[32] = {
      0,    0,    0,    0,    0,    0,    0,    0,    0,    0,    0,    0,    0,    0,    0,    0,
      0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  const __m128i mask = _mm_loadu_si128(reinterpret_cast<const __m128i*>(keep + n));
  const __m128i d = _mm_and_si128(
      _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(last - 16)), _mm_set1_epi8('0')), mask);
  // Each 16-bit lane holds two digits, the first (more significant) in its low byte.
  const __m128i pairs = _mm_add_epi16(
      _mm_mullo_epi16(_mm_and_si128(d, _mm_set1_epi16(0xFF)), _mm_set1_epi16(10)), _mm_srli_epi16(d, 8));
  const __m128i fours = _mm_madd_epi16(pairs, _mm_set1_epi32(100 | (1 << 16)));  // 100 a + b in each 32 bits
  const __m128i eights = _mm_madd_epi16(_mm_packs_epi32(fours, fours), _mm_set1_epi32(10000 | (1 << 16)));
  const auto high = std::uint64_t(std::uint32_t(_mm_cvtsi128_si32(eights)));
  const auto low = std::uint64_t(std::uint32_t(_mm_cvtsi128_si32(_mm_srli_si128(eights, 4))));
  return high * 100000000 + low;
}
#endif

/// Appends the run of decimal digits at `p` (up to `end`) to `m` (m * 10^count + them),
/// moves `p` past it and returns its length; the bytes from `readable` on may be read. The 16
/// digits after the point of most numbers of a stream being most of its bytes, 16 bytes are
/// looked at together where they can be read (SSE2: the run's end in one compare, its value
/// in a few multiply-adds), else eight at a time (fast_float's SWAR digits).
inline long digit_run(const char* readable, const char*& p, const char* end, std::uint64_t& m) {
  const char* const start = p;
#ifdef __SSE2__
  if (end - p >= 16 && p - readable >= 16) {
    // The digits among the 16 bytes: (byte - '0') unsigned at most 9.
    const __m128i d = _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)), _mm_set1_epi8('0'));
    const unsigned digits =
        unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_subs_epu8(d, _mm_set1_epi8(9)), _mm_setzero_si128())));
    const int n = __builtin_ctz(~digits);  // leading digits: 0 to 16
    if (n == 0) return 0;
    m = m * ten_to[n] + sixteen_digits_ending(p + n, n);
    p += n;
    if (n < 16) return n;
    // The 17th to 19th digits (or more, refused) one by one.
    while (p < end && static_cast<unsigned>(*p - '0') < 10) m = 10 * m + std::uint64_t(*p++ - '0');
    return long(p - start);
  }
#elif defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  // The fraction of most numbers (9 to 17 digits) read as sixteen bytes at once, with one
  // test of the room for both eights.
  if (end - p >= 16) {
    std::uint64_t x, y;
    std::memcpy(&x, p, 8);
    std::memcpy(&y, p + 8, 8);
    if (!non_digits(x)) {
      m = m * 100000000 + eight_digits(x);
      if (const std::uint64_t other = non_digits(y)) {
        const int n = __builtin_ctzll(other) / 8;  // leading digits
        if (n) m = m * ten_to[n] + leading_digits(y, n);
        p += 8 + n;
        return 8 + n;
      }
      m = m * 100000000 + eight_digits(y);
      p += 16;  // the 17th to 19th digits (or more, refused) one by one
      while (p < end && static_cast<unsigned>(*p - '0') < 10) m = 10 * m + std::uint64_t(*p++ - '0');
      return long(p - start);
    }
  }
#endif
#if defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  while (end - p >= 8 && p - start <= 19) {
    std::uint64_t x;
    std::memcpy(&x, p, 8);
    const std::uint64_t other = non_digits(x);
    if (!other) {  // eight digits
      m = m * 100000000 + eight_digits(x);
      p += 8;
      continue;
    }
    const int n = __builtin_ctzll(other) / 8;  // leading digits
    if (n == 0) return long(p - start);        // (no digit follows)
    m = m * ten_to[n] + leading_digits(x, n);
    p += n;
    return long(p - start);
  }
#endif
  while (p < end && static_cast<unsigned>(*p - '0') < 10) m = 10 * m + std::uint64_t(*p++ - '0');
  return long(p - start);
}

/// The end of a number `-?D+(.D+)?` at `p` (before `end`) of at most 15 digits before the
/// point and 19 in all, or nullptr for any other form: the form alone, without its value.
/// Every such number is one the stream's parse takes (a finite double, below 1e15 in
/// magnitude, not one std::from_chars finds out of range), so a cell whose value is never
/// used is checked by this. Where 32 bytes are there, their digits are found with SSE2 at once.
inline const char* plain_number_end(const char* p, const char* end) {
  p += p < end && *p == '-';
#ifdef __SSE2__
  if (end - p >= 32) {
    const auto digits16 = [](const char* at) {
      const __m128i d =
          _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(at)), _mm_set1_epi8('0'));
      return std::uint32_t(
          _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_subs_epu8(d, _mm_set1_epi8(9)), _mm_setzero_si128())));
    };
    // Bits 32 on set: the count of digits that lead a shifted mask stops at the window's end.
    const std::uint64_t other = ~std::uint64_t(digits16(p) | digits16(p + 16) << 16);
    const unsigned whole = unsigned(__builtin_ctzll(other));
    if (whole - 1 >= 15) return nullptr;  // none, or over 15
    if (p[whole] != '.') return p + whole;
    // (digits up to the window's end: 31 - whole of them, with the whole ones over 19)
    const unsigned fraction = unsigned(__builtin_ctzll(other >> (whole + 1)));
    if (fraction == 0 || whole + fraction > 19) return nullptr;
    return p + whole + 1 + fraction;
  }
#endif
  const auto digit_count = [end](const char* q) {
    const char* const first = q;
    while (q < end && static_cast<unsigned>(*q - '0') < 10) ++q;
    return long(q - first);
  };
  const long whole = digit_count(p);
  if (whole == 0 || whole > 15) return nullptr;
  p += whole;
  if (p < end && *p == '.') {
    const long fraction = digit_count(++p);
    if (fraction == 0 || whole + fraction > 19) return nullptr;
    p += fraction;
  }
  return p;
}

/// A number `-?D+(.D+)?` of at most 19 digits at `p` (before `end`; the bytes from
/// `readable` on may be read, the text before `p` too where it is there): sets `value` to the
/// double std::from_chars gives for it and returns its end (the caller checks what follows);
/// nullptr for any other form, or where exactness is not certain (the caller then uses
/// from_chars).
inline const char* plain_number(const char* readable, const char* p, const char* end, double& value) {
  const bool minus = p < end && *p == '-';
  p += minus;
  std::uint64_t m = 0;  // all the digits as one integer (wraps past 19 digits, refused then)
  // The digits before the point one by one (ids, indices and coordinates have few); the
  // first two, where two bytes are there, without a test of the end each.
  const char* const first = p;
  unsigned d;
  if (end - p >= 2 && (d = unsigned(p[0] - '0')) < 10) {
    m = d;
    ++p;
    if ((d = unsigned(*p - '0')) < 10) {
      m = 10 * m + d;
      ++p;
    }
  }
  if (p - first == 2 || end - first < 2)  // (more, or the end near)
    while (p < end && static_cast<unsigned>(*p - '0') < 10) m = 10 * m + std::uint64_t(*p++ - '0');
  long digits = long(p - first);
  if (digits == 0) return nullptr;
  int scale = 0;  // digits after the point
  if (p < end && *p == '.') {
    ++p;
    scale = int(digit_run(readable, p, end, m));
    if (scale == 0) return nullptr;  // "5." (from_chars' case)
    digits += scale;
  }
  if (digits > 19) return nullptr;
  constexpr std::uint64_t exact = std::uint64_t(1) << 53;  // every integer up to it is a double
  double v;
  if (m <= exact && scale == 0) {
    v = double(m);  // (ids and counts: no division)
  } else if (m <= exact && scale <= 22) {
    // Both exact: one correctly rounded division (Clinger's fast path).
    static constexpr double tens[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    v = double(m) / tens[scale];
  } else {
#if (defined(__x86_64__) || defined(__i386__)) && LDBL_MANT_DIG == 64
    // 17 to 19 digits: m and 10^scale are exact in the 64-bit significand of
    // x87's long double (scale <= 19 digits), so q is m / 10^scale correctly rounded to 64 bits, and rounding
    // q to 53 bits gives the correctly rounded double unless q lies on a midpoint between two doubles (its 11
    // low bits 10000000000), which is left to from_chars.
    static constexpr long double tens[] = {1e0L,  1e1L,  1e2L,  1e3L,  1e4L,  1e5L,  1e6L,
                                           1e7L,  1e8L,  1e9L,  1e10L, 1e11L, 1e12L, 1e13L,
                                           1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L};
    const long double q = static_cast<long double>(m) / tens[scale];
    std::uint64_t significand;
    std::memcpy(&significand, &q, sizeof significand);  // the low 8 bytes of x87's format
    if ((significand & 0x7FF) == 0x400) return nullptr;
    v = static_cast<double>(q);
#else
    return nullptr;
#endif
  }
  value = minus ? -v : v;
  return p;
}

}  // namespace section::detail
