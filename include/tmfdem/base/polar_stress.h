#ifndef tmfdem_base_polar_stress_h
#define tmfdem_base_polar_stress_h

#include <array>
#include <cmath>

namespace tmfdem
{
  /**
   * The in-plane stress (sxx, syy, sxy) [Pa] in the polar frame about a
   * centre: {sigma_rr, sigma_tt} [Pa] at a point that lies (dx, dy) [m]
   * from the centre, the radial direction (cos a, sin a) = (dx, dy) / r.
   * At the centre itself (r = 0) the frame is the Cartesian one (a = 0).
   * Used by the continuum and the discrete layers' outputs and monitors
   * (Mechanics/Polar frame, Polar centre).
   */
  template <typename Number>
  inline std::array<Number, 2>
  polar_stress(const Number &sxx,
               const Number &syy,
               const Number &sxy,
               const double  dx,
               const double  dy)
  {
    const double r = std::hypot(dx, dy);
    const double c = r > 0. ? dx / r : 1., s = r > 0. ? dy / r : 0.;
    return {{sxx * (c * c) + syy * (s * s) + sxy * (2. * c * s),
             sxx * (s * s) + syy * (c * c) - sxy * (2. * c * s)}};
  }
} // namespace tmfdem

#endif
