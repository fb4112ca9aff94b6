// Floating-point expansion arithmetic (Shewchuk 1997, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", §2).
//
// An expansion is a sum of doubles, nonoverlapping and sorted by increasing magnitude,
// that represents a real number exactly. Sums, differences and products of doubles and
// expansions are computed exactly with error-free transformations (Two-Sum, Two-Product
// via Dekker's split), so the sign of any polynomial in double inputs is exact: it is the
// sign of the largest (last) nonzero term. Zero terms are eliminated as they arise, which
// keeps expansions of exactly representable differences (integer grids, the common
// degenerate input) one or two terms long.
//
// Requires IEEE double with round-to-nearest-even and no extended precision or FMA
// contraction: this header is only included from toolkit/predicates/*.cpp, compiled with
// -ffp-contract=off.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstring>
#include <memory>

namespace delmesh::predicates::detail {

/// x + y = a + b exactly, |y| <= ulp(x)/2.
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

/// x + y = a - b exactly.
inline void two_diff(double a, double b, double& x, double& y) {
  x = a - b;
  const double bv = a - x;
  const double av = x + bv;
  y = (a - av) + (bv - b);
}

/// a = hi + lo with hi, lo of at most 26 significant bits (Dekker).
inline void split(double a, double& hi, double& lo) {
  constexpr double kSplitter = 134217729.0;  // 2^27 + 1
  const double c = kSplitter * a;
  const double big = c - a;
  hi = c - big;
  lo = a - hi;
}

/// x + y = a * b exactly.
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  const double err1 = x - (ahi * bhi);
  const double err2 = err1 - (alo * bhi);
  const double err3 = err2 - (ahi * blo);
  y = (alo * blo) - err3;
}

// ---- Fixed-size expansion routines on caller-provided arrays (adaptive stages) -------
// Shewchuk's FAST-EXPANSION-SUM-ZEROELIM and SCALE-EXPANSION-ZEROELIM on raw arrays, for
// the intermediate adaptive stages whose maximum lengths are known at compile time, so
// that no heap allocation happens on the common near-degenerate path. Each returns the
// number of terms written to h (at least one; a zero value is the single term 0).

/// h = e + f; h must hold elen + flen terms.
inline int sum_into(int elen, const double* e, int flen, const double* f, double* h) {
  int ei = 0, fi = 0, hi = 0;
  auto next = [&]() -> double {
    if (fi >= flen || (ei < elen && std::abs(e[ei]) < std::abs(f[fi]))) return e[ei++];
    return f[fi++];
  };
  if (elen + flen == 0) {
    h[0] = 0.0;
    return 1;
  }
  double q = next();
  for (int k = 1; k < elen + flen; ++k) {
    double qnew, roundoff;
    two_sum(q, next(), qnew, roundoff);
    q = qnew;
    if (roundoff != 0.0) h[hi++] = roundoff;
  }
  if (q != 0.0 || hi == 0) h[hi++] = q;
  return hi;
}

/// h = e * b; h must hold 2 * elen terms.
inline int scale_into(int elen, const double* e, double b, double* h) {
  int hi = 0;
  double q, hh;
  two_product(e[0], b, q, hh);
  if (hh != 0.0) h[hi++] = hh;
  for (int i = 1; i < elen; ++i) {
    double product1, product0, sum, hh2;
    two_product(e[i], b, product1, product0);
    two_sum(q, product0, sum, hh2);
    if (hh2 != 0.0) h[hi++] = hh2;
    q = product1 + sum;  // FAST-TWO-SUM(product1, sum)
    hh = sum - (q - product1);
    if (hh != 0.0) h[hi++] = hh;
  }
  if (q != 0.0 || hi == 0) h[hi++] = q;
  return hi;
}

/// h = a*b - c*d exactly, at most 4 terms.
inline int two_two_diff(double a, double b, double c, double d, double* h) {
  double p[2], q[2];
  two_product(a, b, p[1], p[0]);
  two_product(c, d, q[1], q[0]);
  q[0] = -q[0];
  q[1] = -q[1];
  return sum_into(2, p, 2, q, h);
}

inline double estimate(int n, const double* e) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += e[i];
  return sum;
}

/// An exact real number as a zero-eliminated expansion. Small expansions live inline;
/// longer ones (rare: only near-degenerate inputs with inexact differences) on the heap.
class Expansion {
 public:
  Expansion() = default;
  explicit Expansion(double a) {
    if (a != 0.0) push(a);
  }
  Expansion(const Expansion& other) { assign(other); }
  Expansion& operator=(const Expansion& other) {
    if (this != &other) {
      size_ = 0;
      assign(other);
    }
    return *this;
  }
  Expansion(Expansion&&) = default;
  Expansion& operator=(Expansion&&) = default;

  /// The exact difference a - b of two doubles.
  static Expansion difference(double a, double b) {
    double x, y;
    two_diff(a, b, x, y);
    Expansion e;
    e.reserve(2);
    if (y != 0.0) e.push(y);
    if (x != 0.0) e.push(x);
    return e;
  }

  std::size_t size() const { return size_; }
  const double* data() const { return heap_ ? heap_.get() : inline_; }

  /// Sign of the represented value: -1, 0 or +1.
  int sign() const {
    if (size_ == 0) return 0;
    return data()[size_ - 1] > 0.0 ? 1 : -1;
  }

  /// Largest-magnitude term (an approximation of the value).
  double estimate() const {
    double sum = 0.0;
    for (std::size_t i = 0; i < size_; ++i) sum += data()[i];
    return sum;
  }

  friend Expansion operator+(const Expansion& e, const Expansion& f) { return sum(e, f, false); }
  friend Expansion operator-(const Expansion& e, const Expansion& f) { return sum(e, f, true); }
  friend Expansion operator*(const Expansion& e, const Expansion& f) {
    // sum over the terms of the shorter factor of (longer * term)
    const Expansion& a = e.size() >= f.size() ? e : f;
    const Expansion& b = e.size() >= f.size() ? f : e;
    Expansion result;
    for (std::size_t i = 0; i < b.size(); ++i) result = result + scale(a, b.data()[i]);
    return result;
  }

 private:
  static constexpr std::size_t kInline = 16;

  double* buffer() { return heap_ ? heap_.get() : inline_; }

  void reserve(std::size_t n) {
    if (n <= capacity_) return;
    std::unique_ptr<double[]> grown(new double[n]);
    if (size_) std::memcpy(grown.get(), data(), size_ * sizeof(double));
    heap_ = std::move(grown);
    capacity_ = n;
  }
  void push(double v) { buffer()[size_++] = v; }
  void assign(const Expansion& other) {
    reserve(other.size_);
    if (other.size_) std::memcpy(buffer(), other.data(), other.size_ * sizeof(double));
    size_ = other.size_;
  }

  /// e + f (or e - f): Shewchuk's FAST-EXPANSION-SUM with zero elimination. The terms of
  /// both expansions are merged by magnitude and accumulated with Two-Sum; each exact
  /// roundoff is emitted in increasing order of magnitude. With round-to-nearest-even the
  /// result is again a strongly nonoverlapping expansion (Shewchuk's Theorem 13).
  static Expansion sum(const Expansion& e, const Expansion& f, bool negate_f) {
    const std::size_t elen = e.size(), flen = f.size();
    const double fs = negate_f ? -1.0 : 1.0;
    Expansion h;
    if (flen == 0) return e;
    h.reserve(elen + flen);
    const double* ep = e.data();
    const double* fp = f.data();
    std::size_t ei = 0, fi = 0;
    auto next = [&]() -> double {
      if (fi >= flen || (ei < elen && std::abs(ep[ei]) < std::abs(fp[fi]))) return ep[ei++];
      return fs * fp[fi++];
    };
    double q = next();
    for (std::size_t k = 1; k < elen + flen; ++k) {
      double qnew, roundoff;
      two_sum(q, next(), qnew, roundoff);
      q = qnew;
      if (roundoff != 0.0) h.push(roundoff);
    }
    if (q != 0.0) h.push(q);
    return h;
  }

  /// e * b for a double b: Shewchuk's SCALE-EXPANSION with zero elimination.
  static Expansion scale(const Expansion& e, double b) {
    Expansion h;
    const std::size_t elen = e.size();
    if (elen == 0 || b == 0.0) return h;
    h.reserve(2 * elen);
    const double* ep = e.data();
    double q, hh;
    two_product(ep[0], b, q, hh);
    if (hh != 0.0) h.push(hh);
    for (std::size_t i = 1; i < elen; ++i) {
      double product1, product0;
      two_product(ep[i], b, product1, product0);
      double sum, hh2;
      two_sum(q, product0, sum, hh2);
      if (hh2 != 0.0) h.push(hh2);
      // FAST-TWO-SUM(product1, sum)
      q = product1 + sum;
      const double bv = q - product1;
      hh = sum - bv;
      if (hh != 0.0) h.push(hh);
    }
    if (q != 0.0) h.push(q);
    return h;
  }

  double inline_[kInline];
  std::unique_ptr<double[]> heap_;
  std::size_t size_ = 0;
  std::size_t capacity_ = kInline;
};

}  // namespace delmesh::predicates::detail
