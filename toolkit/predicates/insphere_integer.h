// Exact insphere by integer arithmetic, for the common near-degenerate case in which the
// twelve coordinate differences (a - e, ..., d - e) are exact doubles that share one
// binary scale: points close together (by Sterbenz's lemma their differences are exact),
// e.g. every conflict test of a Delaunay insertion among points nearly on a sphere.
//
// Method: scale every difference by the same power of two so that the largest is below
// 2^62 (or, for points far apart, scale the coordinates so that the largest is below
// 2^61 and subtract as integers); if all scaled values are integers (checked exactly), the insphere
// determinant is a polynomial with integer inputs, evaluated exactly with 128-bit and
// multi-word (64-bit limb) integers: 2x2 minors < 2^125 (__int128), 3x3 minors < 2^189
// (3 words), lifted terms < 2^317 (6 words, two's complement). Scaling by 2^k multiplies
// the determinant by 2^(5k) > 0, so the sign is unchanged. This replaces the expansion
// arithmetic of the generic exact path (Shewchuk 1997) by a few dozen integer multiplies;
// any other input falls back to that path.
//
// Included only from toolkit/predicates/*.cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "toolkit/predicates/expansion.h"

namespace delmesh::predicates::detail {

// 128-bit integers (a GCC/Clang extension on 64-bit targets).
__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

/// A 384-bit two's complement integer (6 limbs, least significant first).
struct Int384 {
  std::uint64_t w[6] = {0, 0, 0, 0, 0, 0};

  void add(const Int384& o) {
    std::uint64_t carry = 0;
    for (int i = 0; i < 6; ++i) {
      const u128 s = static_cast<u128>(w[i]) + o.w[i] + carry;
      w[i] = static_cast<std::uint64_t>(s);
      carry = static_cast<std::uint64_t>(s >> 64);
    }
  }
  void negate() {
    std::uint64_t carry = 1;
    for (auto& x : w) {
      const u128 s = static_cast<u128>(~x) + carry;
      x = static_cast<std::uint64_t>(s);
      carry = static_cast<std::uint64_t>(s >> 64);
    }
  }
  int sign() const {
    if (static_cast<std::int64_t>(w[5]) < 0) return -1;
    for (const auto x : w) {
      if (x != 0) return 1;
    }
    return 0;
  }
};

/// Magnitude of a signed value as (negative, limbs).
struct Magnitude3 {
  bool negative = false;
  std::uint64_t w[3] = {0, 0, 0};
};

inline u128 magnitude(i128 x) { return x < 0 ? static_cast<u128>(-(x + 1)) + 1 : static_cast<u128>(x); }

/// a * b as a 3-limb two's complement number held in an Int384 (sign-extended).
inline Int384 mul_64_128(std::int64_t a, i128 b) {
  const bool negative = (a < 0) != (b < 0);
  const std::uint64_t ma = a < 0 ? static_cast<std::uint64_t>(-(a + 1)) + 1 : static_cast<std::uint64_t>(a);
  const u128 mb = magnitude(b);
  const u128 lo = static_cast<u128>(ma) * static_cast<std::uint64_t>(mb);
  const u128 hi = static_cast<u128>(ma) * static_cast<std::uint64_t>(mb >> 64);
  Int384 r;
  r.w[0] = static_cast<std::uint64_t>(lo);
  const u128 mid = (lo >> 64) + static_cast<std::uint64_t>(hi);
  r.w[1] = static_cast<std::uint64_t>(mid);
  r.w[2] = static_cast<std::uint64_t>(mid >> 64) + static_cast<std::uint64_t>(hi >> 64);
  if (negative) r.negate();
  return r;
}

/// Sum of three products, each below 2^187 in magnitude: a 3x3 minor (< 2^189).
inline Int384 minor3(std::int64_t u, i128 U, std::int64_t v, i128 V, std::int64_t x, i128 X) {
  Int384 r = mul_64_128(u, U);
  r.add(mul_64_128(v, V));
  r.add(mul_64_128(x, X));
  return r;
}

/// lift * m for 0 <= lift < 2^127 and |m| < 2^190 (so the product is below 2^317).
inline Int384 mul_lift(u128 lift, Int384 m) {
  const bool negative = m.sign() < 0;
  if (negative) m.negate();
  const std::uint64_t l[2] = {static_cast<std::uint64_t>(lift), static_cast<std::uint64_t>(lift >> 64)};
  Int384 r;
  for (int i = 0; i < 2; ++i) {
    std::uint64_t carry = 0;
    for (int j = 0; j < 3; ++j) {
      const u128 p = static_cast<u128>(l[i]) * m.w[j] + r.w[i + j] + carry;
      r.w[i + j] = static_cast<std::uint64_t>(p);
      carry = static_cast<std::uint64_t>(p >> 64);
    }
    r.w[i + 3] += carry;
  }
  if (negative) r.negate();
  return r;
}

/// 2^k for -1000 < k < 1000, exactly, without a library call.
inline double pow2(int k) {
  const std::uint64_t bits = static_cast<std::uint64_t>(k + 1023) << 52;
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

/// Scales x by 2^shift; true if the result is an integer below 2^62 in magnitude that
/// scales back to x exactly (so nothing was rounded away).
inline bool scaled_integer(double x, int shift, std::int64_t& out) {
  // Multiplying by a power of two is exact when neither factor nor result leaves the
  // normal range; the round trip below detects any loss. ldexp for extreme shifts.
  const bool moderate = shift > -1000 && shift < 1000;
  const double s = moderate ? x * pow2(shift) : std::ldexp(x, shift);
  if (!(std::abs(s) < 0x1p62) || s != std::trunc(s)) return false;
  if ((moderate ? s * pow2(-shift) : std::ldexp(s, -shift)) != x) return false;
  out = static_cast<std::int64_t>(s);
  return true;
}

/// The twelve differences (a - e, b - e, c - e, d - e) as integers of one common binary
/// scale, each below 2^62 in magnitude; false if no such representation was found.
/// First try: the differences are exact doubles (nearby points); scale them. Second
/// try: the coordinates themselves fit one scale (below 2^61, so that their integer
/// differences stay below 2^62): covers points far apart of similar magnitude.
inline bool integer_differences(const double* a, const double* b, const double* c,
                                const double* d, const double* e, std::int64_t q[12]) {
  const double* p[4] = {a, b, c, d};
  double diff[12];
  double largest = 0.0;
  bool exact = true;
  for (int i = 0; i < 4 && exact; ++i) {
    for (int k = 0; k < 3; ++k) {
      double x, y;
      two_diff(p[i][k], e[k], x, y);
      if (y != 0.0 || !std::isfinite(x)) {
        exact = false;
        break;
      }
      diff[3 * i + k] = x;
      largest = std::max(largest, std::abs(x));
    }
  }
  if (exact) {
    int exponent = 0;
    std::frexp(largest, &exponent);  // largest < 2^exponent (exponent 0 if all zero)
    bool ok = true;
    for (int i = 0; i < 12 && ok; ++i) ok = scaled_integer(diff[i], 62 - exponent, q[i]);
    if (ok) return true;
  }
  largest = std::max({std::abs(e[0]), std::abs(e[1]), std::abs(e[2])});
  for (int i = 0; i < 4; ++i) {
    largest = std::max({largest, std::abs(p[i][0]), std::abs(p[i][1]), std::abs(p[i][2])});
  }
  if (!std::isfinite(largest)) return false;
  int exponent = 0;
  std::frexp(largest, &exponent);
  const int shift = 61 - exponent;
  std::int64_t qe[3];
  for (int k = 0; k < 3; ++k) {
    if (!scaled_integer(e[k], shift, qe[k])) return false;
  }
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) {
      std::int64_t x;
      if (!scaled_integer(p[i][k], shift, x)) return false;
      q[3 * i + k] = x - qe[k];  // both below 2^61: no overflow
    }
  }
  return true;
}

/// Sign of Shewchuk's insphere determinant (the formula of predicates.cpp) when the
/// differences have an integer representation; returns false (sign untouched) otherwise.
inline bool insphere_integer(const double* a, const double* b, const double* c, const double* d,
                             const double* e, int& sign) {
  std::int64_t q[12];
  if (!integer_differences(a, b, c, d, e, q)) return false;
  const std::int64_t aex = q[0], aey = q[1], aez = q[2];
  const std::int64_t bex = q[3], bey = q[4], bez = q[5];
  const std::int64_t cex = q[6], cey = q[7], cez = q[8];
  const std::int64_t dex = q[9], dey = q[10], dez = q[11];
  auto m2 = [](std::int64_t x1, std::int64_t y1, std::int64_t x2, std::int64_t y2) {
    return static_cast<i128>(x1) * y1 - static_cast<i128>(x2) * y2;
  };
  const i128 ab = m2(aex, bey, bex, aey), bc = m2(bex, cey, cex, bey);
  const i128 cd = m2(cex, dey, dex, cey), da = m2(dex, aey, aex, dey);
  const i128 ac = m2(aex, cey, cex, aey), bd = m2(bex, dey, dex, bey);
  const Int384 abc = minor3(aez, bc, -bez, ac, cez, ab);
  const Int384 bcd = minor3(bez, cd, -cez, bd, dez, bc);
  const Int384 cda = minor3(cez, da, dez, ac, aez, cd);
  const Int384 dab = minor3(dez, ab, aez, bd, bez, da);
  auto lift = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<u128>(static_cast<i128>(x) * x) + static_cast<u128>(static_cast<i128>(y) * y) +
           static_cast<u128>(static_cast<i128>(z) * z);
  };
  // det = (dlift*abc - clift*dab) + (blift*cda - alift*bcd)
  Int384 det = mul_lift(lift(dex, dey, dez), abc);
  Int384 t = mul_lift(lift(cex, cey, cez), dab);
  t.negate();
  det.add(t);
  det.add(mul_lift(lift(bex, bey, bez), cda));
  t = mul_lift(lift(aex, aey, aez), bcd);
  t.negate();
  det.add(t);
  sign = det.sign();
  return true;
}

}  // namespace delmesh::predicates::detail
