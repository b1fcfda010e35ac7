// geometry/kernel/expansion.cpp: expansion arithmetic (see expansion.h for the model,
// the requirements on floating point, and the references).
#include "geometry/kernel/expansion.h"

#include <cmath>
#include <cstring>

namespace skinmesh::geometry {

// Expansion Operations Definitions -------------------------------------------

int grow_expansion(int elen, const double* e, double b, double* h) {
  // Carry Q upward through the components; every round-off word is kept.
  double q = b;
  int k = 0;
  for (int i = 0; i < elen; ++i) {
    const double ei = e[i];  // read before h[k] (k <= i) is written: aliasing is safe
    double sum, err;
    two_sum(q, ei, sum, err);
    if (err != 0.0) h[k++] = err;
    q = sum;
  }
  if (q != 0.0) h[k++] = q;
  return k;
}

namespace {

// Merge of e and (sign * f) by increasing magnitude followed by a single two-sum
// pass. The first addition may use fast_two_sum because the second merged
// component is at least as large as the first.
int merge_sum(int elen, const double* e, int flen, const double* f, double fsign, double* h) {
  if (elen == 0 && flen == 0) return 0;
  int i = 0, j = 0;
  auto next = [&]() -> double {
    if (i < elen && (j >= flen || std::abs(e[i]) < std::abs(f[j]))) return e[i++];
    return fsign * f[j++];
  };
  const int total = elen + flen;
  double q = next();
  int k = 0;
  if (total >= 2) {
    double sum, err;
    fast_two_sum(next(), q, sum, err);
    if (err != 0.0) h[k++] = err;
    q = sum;
    for (int m = 2; m < total; ++m) {
      two_sum(q, next(), sum, err);
      if (err != 0.0) h[k++] = err;
      q = sum;
    }
  }
  if (q != 0.0) h[k++] = q;
  return k;
}

}  // namespace

int expansion_sum(int elen, const double* e, int flen, const double* f, double* h) {
  return merge_sum(elen, e, flen, f, 1.0, h);
}

int expansion_diff(int elen, const double* e, int flen, const double* f, double* h) {
  return merge_sum(elen, e, flen, f, -1.0, h);
}

int scale_expansion(int elen, const double* e, double b, double* h) {
  if (elen == 0 || b == 0.0) return 0;
  double bhi, blo;
  split(b, bhi, blo);
  double q, err;
  two_product_presplit(e[0], b, bhi, blo, q, err);
  int k = 0;
  if (err != 0.0) h[k++] = err;
  for (int i = 1; i < elen; ++i) {
    // e[i] * b = p1 + p0; add p0 to the carry, then p1 (which dominates).
    double p1, p0, sum;
    two_product_presplit(e[i], b, bhi, blo, p1, p0);
    two_sum(q, p0, sum, err);
    if (err != 0.0) h[k++] = err;
    fast_two_sum(p1, sum, q, err);
    if (err != 0.0) h[k++] = err;
  }
  if (q != 0.0) h[k++] = q;
  return k;
}

int expansion_product(int elen, const double* e, int flen, const double* f, double* h, double* scratch) {
  if (elen == 0 || flen == 0) return 0;
  // Layout of scratch: [term: 2*elen][acc: 2*elen*flen]. The running sum
  // ping-pongs between acc and h so that it ends in h.
  double* term = scratch;
  double* acc = scratch + 2 * elen;
  // Decide the buffer for the first partial sum so the last one lands in h:
  // partial j (0-based) goes to h iff (flen - 1 - j) is even.
  double* cur = ((flen - 1) % 2 == 0) ? h : acc;
  double* other = (cur == h) ? acc : h;
  int len = scale_expansion(elen, e, f[0], cur);
  for (int j = 1; j < flen; ++j) {
    const int tlen = scale_expansion(elen, e, f[j], term);
    len = expansion_sum(len, cur, tlen, term, other);
    double* t = cur;
    cur = other;
    other = t;
  }
  return len;
}

int compress_expansion(int elen, const double* e, double* h) {
  if (elen == 0) return 0;
  // Top-down pass: accumulate from the largest component, emitting a word
  // whenever a carry leaves a nonzero remainder (written from the top of h).
  int bottom = elen - 1;
  double q = e[bottom];
  for (int i = elen - 2; i >= 0; --i) {
    double sum, err;
    fast_two_sum(q, e[i], sum, err);
    if (err != 0.0) {
      h[bottom--] = sum;
      q = err;
    } else {
      q = sum;
    }
  }
  h[bottom] = q;
  // Bottom-up pass: renormalise into a nonadjacent expansion.
  int top = 0;
  for (int i = bottom + 1; i < elen; ++i) {
    double sum, err;
    fast_two_sum(h[i], q, sum, err);
    if (err != 0.0) h[top++] = err;
    q = sum;
  }
  if (q != 0.0) h[top++] = q;
  return top;
}

Sign expansion_sign(int elen, const double* e) {
  for (int i = elen - 1; i >= 0; --i) {
    if (e[i] != 0.0) return sign_of(e[i]);
  }
  return Sign::Zero;
}

}  // namespace skinmesh::geometry
