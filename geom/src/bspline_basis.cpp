#include "cncc/geom/bspline_basis.h"

#include <algorithm>
#include <array>

namespace cncc::geom {

namespace {

using KnotDifferences = std::array<double, kMaxDegree + 1>;

} // namespace

BasisValues basisFunctions(const KnotVector& knots, int span, double t) {
  // The NURBS Book A2.2: build N_{.,j} from N_{.,j-1} for j = 1..p, reusing the shared
  // factor of neighbouring functions so each level costs j divisions.
  int p = knots.degree();
  BasisValues basis(p + 1);
  KnotDifferences left{}, right{};
  basis[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      double shared = basis[r] / (right[r + 1] + left[j - r]);
      basis[r] = saved + right[r + 1] * shared;
      saved = left[j - r] * shared;
    }
    basis[j] = saved;
  }
  return basis;
}

BasisDerivatives basisFunctionDerivatives(const KnotVector& knots, int span, double t, int order) {
  // The NURBS Book A2.3. `table` holds the basis functions of every degree 0..p in its
  // upper triangle (column j = degree j) and the knot differences in its lower one;
  // derivatives are then differences of lower-degree functions over knot differences.
  int p = knots.degree();
  BasisDerivatives result = BasisDerivatives::Zero(order + 1, p + 1);
  std::array<std::array<double, kMaxDegree + 1>, kMaxDegree + 1> table{};
  KnotDifferences left{}, right{};
  table[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      table[j][r] = right[r + 1] + left[j - r];
      double shared = table[r][j - 1] / table[j][r];
      table[r][j] = saved + right[r + 1] * shared;
      saved = left[j - r] * shared;
    }
    table[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j)
    result(0, j) = table[j][p];

  int highest = std::min(order, p); // a degree-p piece has no higher derivative
  // Two alternating rows of the coefficients a_{k,j} of the k-th derivative.
  std::array<std::array<double, kMaxDegree + 1>, 2> a{};
  for (int r = 0; r <= p; ++r) {
    int current = 0, next = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= highest; ++k) {
      double derivative = 0.0;
      int rk = r - k, pk = p - k;
      if (r >= k) {
        a[next][0] = a[current][0] / table[pk + 1][rk];
        derivative = a[next][0] * table[rk][pk];
      }
      int firstJ = rk >= -1 ? 1 : -rk;
      int lastJ = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = firstJ; j <= lastJ; ++j) {
        a[next][j] = (a[current][j] - a[current][j - 1]) / table[pk + 1][rk + j];
        derivative += a[next][j] * table[rk + j][pk];
      }
      if (r <= pk) {
        a[next][k] = -a[current][k - 1] / table[pk + 1][r];
        derivative += a[next][k] * table[r][pk];
      }
      result(k, r) = derivative;
      std::swap(current, next);
    }
  }
  // Multiply by p! / (p - k)!.
  double factor = p;
  for (int k = 1; k <= highest; ++k) {
    result.row(k) *= factor;
    factor *= (p - k);
  }
  return result;
}

} // namespace cncc::geom
