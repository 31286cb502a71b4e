/**
 * @file
 * The constant-strain triangle at finite strain (paper Sec. 2, 4.1-4.2 with
 * the corrections of the theory manual): deformation gradient from the
 * current and initial element bases, the multiplicative thermal split
 * F = F_T F_e with F_T = s I, the compressible neo-Hookean-type Cauchy
 * stress of Eq. 44 evaluated with the ELASTIC part F_e, and the viscous
 * stress 2 eta D with D = sym(dF/dt F^-1) (Eqs. 45-46).
 *
 * The constitutive law (Lame constants per idealisation, thermal stretch,
 * Eq. 44 on F_e) is the core both layers share, base/constitutive.h; this
 * header adds the triangle's kinematics and forces around it. Everything
 * here is plain inline arithmetic on doubles: these functions run once per
 * triangle per explicit step. The 2x2 algebra is Eigen's (Matrix2 =
 * Eigen::Matrix2d: F = basis * inverse_basis, F.determinant(),
 * F.inverse()).
 */
#ifndef tmfdem_discrete_solid_h
#define tmfdem_discrete_solid_h

#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <tmfdem/base/constitutive.h>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * A 2x2 matrix: Eigen's fixed-size type (no allocation; its product,
     * determinant and inverse form every entry in the same order as the
     * hand-written code they replaced, so results are bitwise unchanged:
     * doc/performance.md, "Eigen for the element algebra").
     */
    using Matrix2 = Eigen::Matrix2d;

    /** The matrix [a00, a01; a10, a11]. */
    inline Matrix2
    matrix2(const double a00,
            const double a01,
            const double a10,
            const double a11)
    {
      Matrix2 m;
      m << a00, a01, a10, a11;
      return m;
    }

    // The constitutive law itself (idealisation, Lame constants, thermal
    // stretch, Eq. 44 and its energy) is the one core of both layers in
    // base/constitutive.h; the discrete layer uses it under its own names.
    using constitutive::Idealisation;
    using constitutive::lame_constants;
    using constitutive::LameConstants;
    using constitutive::Stress2;
    using constitutive::thermal_stretch;

    /**
     * The element basis [x1-x0, x2-x0; y1-y0, y2-y0] of a triangle with the
     * given node coordinates [m] (paper Eq. 39).
     */
    inline Matrix2
    element_basis(const double x0,
                  const double y0,
                  const double x1,
                  const double y1,
                  const double x2,
                  const double y2)
    {
      return matrix2(x1 - x0, x2 - x0, y1 - y0, y2 - y0);
    }

    /**
     * Cauchy stress of paper Eq. 44 on the elastic deformation gradient
     * @p Fe [Pa] (constitutive::elastic_stress()).
     */
    inline Stress2
    elastic_stress(const Matrix2 &Fe, const LameConstants &lame)
    {
      return constitutive::elastic_stress(Fe(0, 0),
                                          Fe(0, 1),
                                          Fe(1, 0),
                                          Fe(1, 1),
                                          lame);
    }

    /** sqrt 2, of the Mandel components below. */
    constexpr double mandel_sqrt2 = 1.4142135623730951;

    /** Green-Lagrange strain E = (F_e^T F_e - I) / 2 of @p Fe in Mandel
     *  components (xx, yy, sqrt 2 xy) [-]. */
    inline std::array<double, 3>
    green_lagrange_mandel(const Matrix2 &Fe)
    {
      const double f00 = Fe(0, 0), f01 = Fe(0, 1);
      const double f10 = Fe(1, 0), f11 = Fe(1, 1);
      return {{0.5 * (f00 * f00 + f10 * f10 - 1.),
               0.5 * (f01 * f01 + f11 * f11 - 1.),
               mandel_sqrt2 * 0.5 * (f00 * f01 + f10 * f11)}};
    }

    /**
     * The anisotropic correction of an element's stress [Pa]
     * (joint_compliance.h): the Cauchy stress of the second Piola-Kirchhoff
     * stress Delta C : E, E = (F_e^T F_e - I) / 2, that is
     * F_e (Delta C : E) F_e^T / J, with @p delta_C the Mandel components
     * (11, 22, 33, 12, 13, 23) [Pa]. Linear in the small strain, objective,
     * and the derivative of anisotropic_energy_density().
     */
    inline Stress2
    anisotropic_stress(const Matrix2 &Fe, const double *delta_C)
    {
      const auto   e = green_lagrange_mandel(Fe);
      const double Sxx =
        delta_C[0] * e[0] + delta_C[3] * e[1] + delta_C[4] * e[2];
      const double Syy =
        delta_C[3] * e[0] + delta_C[1] * e[1] + delta_C[5] * e[2];
      const double Sxy =
        (delta_C[4] * e[0] + delta_C[5] * e[1] + delta_C[2] * e[2]) /
        mandel_sqrt2;
      const double f00 = Fe(0, 0), f01 = Fe(0, 1);
      const double f10 = Fe(1, 0), f11 = Fe(1, 1);
      const double inverse_J = 1. / (f00 * f11 - f01 * f10);
      const double a00 = f00 * Sxx + f01 * Sxy, a01 = f00 * Sxy + f01 * Syy;
      const double a10 = f10 * Sxx + f11 * Sxy, a11 = f10 * Sxy + f11 * Syy;
      return {(a00 * f00 + a01 * f01) * inverse_J,
              (a10 * f10 + a11 * f11) * inverse_J,
              (a00 * f10 + a01 * f11) * inverse_J};
    }

    /** The energy of anisotropic_stress() per unit area of the stress-free
     *  configuration, E : Delta C : E / 2 [J/m^2]. */
    inline double
    anisotropic_energy_density(const Matrix2 &Fe, const double *delta_C)
    {
      const auto e = green_lagrange_mandel(Fe);
      return 0.5 * (delta_C[0] * e[0] * e[0] + delta_C[1] * e[1] * e[1] +
                    delta_C[2] * e[2] * e[2]) +
             delta_C[3] * e[0] * e[1] + delta_C[4] * e[0] * e[2] +
             delta_C[5] * e[1] * e[2];
    }

    /**
     * Strain energy per unit area of the stress-free configuration [J/m^2]
     * whose derivative is Eq. 44 (constitutive::strain_energy_density()).
     */
    inline double
    strain_energy_density(const Matrix2 &Fe, const LameConstants &lame)
    {
      return constitutive::strain_energy_density(Fe(0, 0),
                                                 Fe(0, 1),
                                                 Fe(1, 0),
                                                 Fe(1, 1),
                                                 lame);
    }

    /**
     * Nodal forces of a constant-stress triangle [N/m]: f_a = -A sigma
     * grad N_a in the current configuration, which is -1/2 sigma n_a with
     * n_a the opposite edge rotated outward. Coordinates of the current
     * nodes [m]; results added to nothing, written to @p f (x0,y0,x1,...).
     */
    inline void
    nodal_forces(const Stress2 &s,
                 const double   x0,
                 const double   y0,
                 const double   x1,
                 const double   y1,
                 const double   x2,
                 const double   y2,
                 double        *f)
    {
      // grad N_a * 2A: node 0: (y1 - y2, x2 - x1), node 1: (y2 - y0, x0 - x2),
      // node 2: (y0 - y1, x1 - x0)
      const double g0x = y1 - y2, g0y = x2 - x1;
      const double g1x = y2 - y0, g1y = x0 - x2;
      const double g2x = y0 - y1, g2y = x1 - x0;
      f[0] = -0.5 * (s.xx * g0x + s.xy * g0y);
      f[1] = -0.5 * (s.xy * g0x + s.yy * g0y);
      f[2] = -0.5 * (s.xx * g1x + s.xy * g1y);
      f[3] = -0.5 * (s.xy * g1x + s.yy * g1y);
      f[4] = -0.5 * (s.xx * g2x + s.xy * g2y);
      f[5] = -0.5 * (s.xy * g2x + s.yy * g2y);
    }
  } // namespace discrete
} // namespace tmfdem

#endif
