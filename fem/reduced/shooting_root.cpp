#include "fem/reduced/shooting_root.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace softarm::fem {
namespace {

struct Point {
  double m, f;
};

/// The evaluations so far: the bracket (nearest pair of opposite signs) and the point of least |f|.
class Search {
 public:
  Search(const std::function<double(double)>& f, const ShootingSettings& s) : f_(f), s_(s) {}

  double evaluate(double m) {
    ++count_;
    last_ = {m, f_(m)};
    const Point& p = last_;
    if (!std::isfinite(p.f)) return p.f;
    if (!best_ || std::abs(p.f) < std::abs(best_->f)) best_ = p;
    if (refining_) return p.f;  // refine() moves the bracket's ends itself
    (p.f > 0 ? positive_ : negative_).push_back(p);
    update_bracket(p);
    return p.f;
  }
  bool done() const { return std::isfinite(last_.f) && std::abs(last_.f) <= s_.tolerance * s_.scale; }
  bool bracketed() const { return lo_.has_value(); }
  const Point& last() const { return last_; }
  const Point& best() const { return *best_; }
  bool any_defined() const { return best_.has_value(); }
  int count() const { return count_; }

  /// Illinois regula falsi inside the bracket; an undefined trial is replaced by the midpoint.
  bool refine() {
    refining_ = true;
    int side = 0;  // which end was kept last (Illinois halves its value when kept twice)
    double flo = lo_->f, fhi = hi_->f;
    for (int it = 0; it < s_.bracket_iterations; ++it) {
      double m = (lo_->m * fhi - hi_->m * flo) / (fhi - flo);
      if (!(m > std::min(lo_->m, hi_->m) && m < std::max(lo_->m, hi_->m))) m = 0.5 * (lo_->m + hi_->m);
      double value = evaluate(m);
      if (!std::isfinite(value)) value = evaluate(0.5 * (lo_->m + hi_->m));
      if (!std::isfinite(value)) return false;
      if (done()) return true;
      if ((value > 0) == (lo_->f > 0)) {
        lo_ = last_, flo = value;
        if (side == -1) fhi *= 0.5;
        side = -1;
      } else {
        hi_ = last_, fhi = value;
        if (side == +1) flo *= 0.5;
        side = +1;
      }
      if (std::abs(hi_->m - lo_->m) <= 1e-15 * std::max(1.0, std::abs(lo_->m))) return false;
    }
    return false;
  }

  /// Outwards from the point of least |f|, both ways, until a sign change.
  void search_outwards() {
    const Point centre = *best_;
    for (const double direction : {+1.0, -1.0}) {
      Point defined = centre;
      double step = s_.first_step * s_.scale;
      for (int it = 0; it < 40 && !bracketed(); ++it) {
        const double m = defined.m + direction * step;
        if (std::isfinite(evaluate(m))) {
          defined = last_;
          step *= 2;
          continue;
        }
        // The edge: bisect between the defined point and the undefined one; the band lies there.
        double undefined = m;
        for (int k = 0; k < 50 && !bracketed(); ++k) {
          const double mid = 0.5 * (defined.m + undefined);
          if (std::isfinite(evaluate(mid))) defined = last_;
          else undefined = mid;
          if (std::abs(undefined - defined.m) <= 1e-14 * std::max(1.0, std::abs(mid))) break;
        }
        break;
      }
      if (bracketed()) return;
    }
  }

 private:
  void update_bracket(const Point& p) {
    const auto& others = p.f > 0 ? negative_ : positive_;
    for (const Point& q : others)
      if (!lo_ || std::abs(p.m - q.m) < std::abs(hi_->m - lo_->m)) lo_ = p, hi_ = q;
  }

  const std::function<double(double)>& f_;
  const ShootingSettings& s_;
  int count_ = 0;
  bool refining_ = false;
  Point last_{0, 0};
  std::optional<Point> best_, lo_, hi_;
  std::vector<Point> positive_, negative_;
};

ShootingRoot result(const Search& search) {
  return {search.last().m, search.last().f, search.done(), search.count()};
}

}  // namespace

ShootingRoot shooting_root(const std::function<double(double)>& f, double start, const ShootingSettings& s) {
  Search search(f, s);
  double m0 = start, f0 = search.evaluate(m0);
  if (search.done()) return result(search);
  if (!std::isfinite(f0)) return result(search);  // the warm start itself is undefined
  double m1 = m0 + s.first_step * s.scale, f1 = search.evaluate(m1);
  // 1. Secant, backing off towards the last defined point from an undefined trial.
  for (int it = 0; it < s.secant_iterations && !search.bracketed(); ++it) {
    for (int k = 0; k < 40 && !std::isfinite(f1); ++k) f1 = search.evaluate(m1 = 0.5 * (m0 + m1));
    if (!std::isfinite(f1)) return result(search);
    if (search.done()) return result(search);
    if (f1 == f0) break;
    const double m2 = std::clamp(m1 - f1 * (m1 - m0) / (f1 - f0), m1 - s.max_step * s.scale, m1 + s.max_step * s.scale);
    m0 = m1, f0 = f1, m1 = m2;
    f1 = search.evaluate(m1);
    if (search.done()) return result(search);
  }
  // 3. No sign change seen: look for one.
  if (!search.bracketed()) search.search_outwards();
  // 2. Inside the bracket.
  if (search.bracketed()) search.refine();
  return result(search);
}

}  // namespace softarm::fem
