#include "fem/reduced/confined_wall.hpp"

#include <algorithm>
#include <cmath>
#include "fem/core/angles.hpp"

namespace softarm::fem {
namespace {

// 8-point Gauss–Legendre on [−1, 1].
constexpr double kGaussX[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                               0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
constexpr double kGaussW[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

// dW/dλ of the wall at reference radius R: Σ_a ∂W/∂c_a · dc_a/dλ, c = (λ², r²/R², R²/(λ² r²)).
double stress_density(const HyperelasticLaw& law, double R, double Ri, double l) {
  const double r2 = Ri * Ri - (Ri * Ri - R * R) / l, dr2 = (Ri * Ri - R * R) / (l * l);
  const double c1 = l * l, c2 = r2 / (R * R), c3 = R * R / (l * l * r2);
  const Jet3 w = law.principal_energy_at(c1, c2, c3);
  const double dc1 = 2 * l, dc2 = dr2 / (R * R), dc3 = -R * R * (2 * l * r2 + l * l * dr2) / (l * l * l * l * r2 * r2);
  return w.g[0] * dc1 + w.g[1] * dc2 + w.g[2] * dc3;
}
}  // namespace

double confined_wall_min_stretch(double Rc, double Ri) { return 1 - (Rc * Rc) / (Ri * Ri); }

FibreLaw confined_wall_law(const HyperelasticLaw& law, double Rc, double Ri, int points) {
  const double area = kPi * (Ri * Ri - Rc * Rc);
  const auto mean_stress = [&law, Rc, Ri, area](double l) {
    // Gauss–Legendre in R² (the measure 2πR dR = π d(R²)), two panels: the integrand is steep near R_c.
    double sum = 0;
    const double a = Rc * Rc, b = Ri * Ri, m = 0.5 * (a + b);
    for (const auto& [lo, hi] : {std::pair{a, m}, std::pair{m, b}})
      for (int g = 0; g < 8; ++g) {
        const double R2 = 0.5 * (lo + hi) + 0.5 * (hi - lo) * kGaussX[g];
        sum += 0.5 * (hi - lo) * kGaussW[g] * kPi * stress_density(law, std::sqrt(R2), Ri, l);
      }
    return sum / area;
  };
  const double lo = std::max(0.3, confined_wall_min_stretch(Rc, Ri) + 0.05);
  return FibreLaw(mean_stress, lo, 6.0, points);
}

}  // namespace softarm::fem
