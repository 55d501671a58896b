#pragma once
// Second-order forward-mode automatic differentiation in N variables.
//
// A Jet carries a value, its gradient and its Hessian with respect to N
// independent variables. Material laws write their strain energy once, as a
// function of the principal invariants (eigenvalues of C), and obtain the
// exact first and second derivatives needed by the stress and tangent without
// hand-derived formulas (which is where most hyperelastic bugs live).
//
// Every elementary function f is lifted with the chain rule
//   v' = f(v),  g' = f'(v) g,  H' = f'(v) H + f''(v) g gᵀ.
#include <Eigen/Core>
#include <cmath>

namespace softarm::fem {

template <int N>
struct Jet {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  double v = 0.0;
  Vec g = Vec::Zero();
  Mat h = Mat::Zero();

  Jet() = default;
  Jet(double value) : v(value) {}  // NOLINT: constants promote implicitly
  static Jet variable(double value, int index) {
    Jet j(value);
    j.g[index] = 1.0;
    return j;
  }

  // Applies a scalar function given its value and first two derivatives at v.
  Jet chain(double f, double df, double d2f) const {
    Jet r;
    r.v = f;
    r.g = df * g;
    r.h = df * h + d2f * g * g.transpose();
    return r;
  }

  Jet& operator+=(const Jet& o) { v += o.v; g += o.g; h += o.h; return *this; }
  Jet& operator-=(const Jet& o) { v -= o.v; g -= o.g; h -= o.h; return *this; }
  Jet& operator*=(const Jet& o) { *this = *this * o; return *this; }

  friend Jet operator+(Jet a, const Jet& b) { return a += b; }
  friend Jet operator-(Jet a, const Jet& b) { return a -= b; }
  friend Jet operator-(const Jet& a) {
    Jet r;
    r.v = -a.v; r.g = -a.g; r.h = -a.h;
    return r;
  }
  friend Jet operator*(const Jet& a, const Jet& b) {
    Jet r;
    r.v = a.v * b.v;
    r.g = a.v * b.g + b.v * a.g;
    r.h = a.v * b.h + b.v * a.h + a.g * b.g.transpose() + b.g * a.g.transpose();
    return r;
  }
  friend Jet operator*(double s, Jet a) { a.v *= s; a.g *= s; a.h *= s; return a; }
  friend Jet operator*(Jet a, double s) { return s * a; }
  friend Jet operator/(const Jet& a, const Jet& b) { return a * reciprocal(b); }
  friend Jet operator/(Jet a, double s) { return (1.0 / s) * a; }
  friend Jet operator/(double s, const Jet& b) { return s * reciprocal(b); }

  friend Jet reciprocal(const Jet& a) {
    const double i = 1.0 / a.v;
    return a.chain(i, -i * i, 2.0 * i * i * i);
  }
  // x^p for real p (x > 0).
  friend Jet pow(const Jet& a, double p) {
    const double f = std::pow(a.v, p);
    return a.chain(f, p * f / a.v, p * (p - 1.0) * f / (a.v * a.v));
  }
  friend Jet sqrt(const Jet& a) { return pow(a, 0.5); }
  friend Jet log(const Jet& a) { return a.chain(std::log(a.v), 1.0 / a.v, -1.0 / (a.v * a.v)); }
  friend Jet exp(const Jet& a) {
    const double e = std::exp(a.v);
    return a.chain(e, e, e);
  }
  // Integer power: exact at a = 0 too, where pow(x, p) would divide by zero.
  friend Jet ipow(const Jet& a, int n) {
    if (n == 0) return Jet(1.0);
    const double f = std::pow(a.v, n);
    const double df = n * std::pow(a.v, n - 1);
    const double d2f = n > 1 ? n * (n - 1) * std::pow(a.v, n - 2) : 0.0;
    return a.chain(f, df, d2f);
  }
};

}  // namespace softarm::fem
