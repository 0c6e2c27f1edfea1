// Tait equation of state (Monaghan 1994; Batchelor 1967), as in DualSPHysics:
//   p = B [ (rho/rho0)^gamma - 1 ],   B = c0^2 rho0 / gamma.
// c0 is a constant numerical speed of sound (weak compressibility), never a local one.
#pragma once

#include <cmath>
#include <optional>

namespace vrsph {

// [eos], as the case gives it: gamma and the choice of c0 (made at set-up, common to all levels).
struct EosParams {
  double gamma = 7.0;                 // exponent of the Tait EOS (dimensionless)
  std::optional<double> max_speed;    // expected largest speed (m/s); absent: sqrt(|g| H) with
                                      // gravity, else the largest initial speed
  double sound_speed_factor = 20.0;   // c0 = factor * max_speed (dimensionless)
  std::optional<double> sound_speed;  // c0 itself (m/s); overrides the two above

  bool operator==(const EosParams&) const = default;
};

struct TaitEos {
  double rho0 = 1000.0;
  double gamma = 7.0;
  double c0 = 10.0;
  double b = 0.0;  // B = c0^2 rho0 / gamma

  TaitEos() = default;
  TaitEos(double rho0_, double gamma_, double c0_)
      : rho0(rho0_), gamma(gamma_), c0(c0_), b(c0_ * c0_ * rho0_ / gamma_) {}

  double pressure(double rho) const {
    if (gamma == 7.0) return pressure_gamma7(rho);  // exact, several times cheaper than std::pow
    return b * (std::pow(rho / rho0, gamma) - 1.0);
  }
  // pressure() where gamma is 7, without the test (for loops that test once).
  double pressure_gamma7(double rho) const {
    const double ratio = rho / rho0;
    const double r2 = ratio * ratio;
    return b * (r2 * r2 * r2 * ratio - 1.0);
  }

  // Inverse: the density at which the EOS gives pressure p.
  double density(double p) const { return rho0 * std::pow(1.0 + p / b, 1.0 / gamma); }
};

}  // namespace vrsph
