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
 * header adds the triangle's kinematics and forces around it: the
 * anisotropic correction and the nodal forces as templates on the number
 * type (double or a vector of doubles, one triangle per lane), which
 * element_kernel.h assembles into the one element kernel of the explicit
 * loop, and Matrix2 (Eigen::Matrix2d) versions of them for the set-up,
 * stress recovery and tests.
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

    /** Green-Lagrange strain E = (F_e^T F_e - I) / 2 of F_e = [f00, f01;
     *  f10, f11] in Mandel components (xx, yy, sqrt 2 xy) [-], written to
     *  @p e. @p Number: double or a vector of doubles. */
    template <typename Number>
    __attribute__((always_inline)) inline void
    green_lagrange_mandel(const Number f00,
                          const Number f01,
                          const Number f10,
                          const Number f11,
                          Number      *e)
    {
      e[0] = 0.5 * (f00 * f00 + f10 * f10 - 1.);
      e[1] = 0.5 * (f01 * f01 + f11 * f11 - 1.);
      e[2] = mandel_sqrt2 * 0.5 * (f00 * f01 + f10 * f11);
    }

    /** The same for a Matrix2 @p Fe. */
    inline std::array<double, 3>
    green_lagrange_mandel(const Matrix2 &Fe)
    {
      std::array<double, 3> e;
      green_lagrange_mandel(Fe(0, 0), Fe(0, 1), Fe(1, 0), Fe(1, 1), e.data());
      return e;
    }

    /**
     * The anisotropic correction of an element's stress [Pa]
     * (joint_compliance.h): the Cauchy stress of the second Piola-Kirchhoff
     * stress Delta C : E, E = (F_e^T F_e - I) / 2, that is
     * F_e (Delta C : E) F_e^T / J, with @p c the Mandel components of
     * Delta C (11, 22, 33, 12, 13, 23) [Pa], for F_e = [f00, f01; f10, f11]
     * [-]; written to @p sxx, @p syy, @p sxy. Linear in the small strain,
     * objective, and the derivative of anisotropic_energy_density().
     * @p Number: double or a vector of doubles.
     */
    template <typename Number>
    __attribute__((always_inline)) inline void
    anisotropic_stress(const Number  f00,
                       const Number  f01,
                       const Number  f10,
                       const Number  f11,
                       const Number *c,
                       Number       &sxx,
                       Number       &syy,
                       Number       &sxy)
    {
      Number e[3];
      green_lagrange_mandel(f00, f01, f10, f11, e);
      const Number Sxx = c[0] * e[0] + c[3] * e[1] + c[4] * e[2];
      const Number Syy = c[3] * e[0] + c[1] * e[1] + c[5] * e[2];
      const Number Sxy =
        (c[4] * e[0] + c[5] * e[1] + c[2] * e[2]) / mandel_sqrt2;
      const Number inverse_J = 1. / (f00 * f11 - f01 * f10);
      const Number a00 = f00 * Sxx + f01 * Sxy, a01 = f00 * Sxy + f01 * Syy;
      const Number a10 = f10 * Sxx + f11 * Sxy, a11 = f10 * Sxy + f11 * Syy;
      sxx = (a00 * f00 + a01 * f01) * inverse_J;
      syy = (a10 * f10 + a11 * f11) * inverse_J;
      sxy = (a00 * f10 + a01 * f11) * inverse_J;
    }

    /** The same for a Matrix2 @p Fe and Delta C @p delta_C [Pa]. */
    inline Stress2
    anisotropic_stress(const Matrix2 &Fe, const double *delta_C)
    {
      Stress2 s;
      anisotropic_stress(Fe(0, 0),
                         Fe(0, 1),
                         Fe(1, 0),
                         Fe(1, 1),
                         delta_C,
                         s.xx,
                         s.yy,
                         s.xy);
      return s;
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
     * n_a the opposite edge rotated outward. Stress @p sxx, @p syy, @p sxy
     * [Pa], current node coordinates @p x, @p y [m]; written to @p fx,
     * @p fy (node by node). @p Number: double or a vector of doubles.
     */
    template <typename Number>
    __attribute__((always_inline)) inline void
    nodal_forces(const Number  sxx,
                 const Number  syy,
                 const Number  sxy,
                 const Number *x,
                 const Number *y,
                 Number       *fx,
                 Number       *fy)
    {
      // grad N_a * 2A: node 0: (y1 - y2, x2 - x1), node 1: (y2 - y0, x0 - x2),
      // node 2: (y0 - y1, x1 - x0)
      const Number gx[3] = {y[1] - y[2], y[2] - y[0], y[0] - y[1]};
      const Number gy[3] = {x[2] - x[1], x[0] - x[2], x[1] - x[0]};
      for (unsigned int k = 0; k < 3; ++k)
        {
          fx[k] = -0.5 * (sxx * gx[k] + sxy * gy[k]);
          fy[k] = -0.5 * (sxy * gx[k] + syy * gy[k]);
        }
    }

    /** The same for a Stress2 @p s and nodes (x0, y0) ... (x2, y2) [m];
     *  written to @p f (x0, y0, x1, ...) [N/m]. */
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
      const double x[3] = {x0, x1, x2}, y[3] = {y0, y1, y2};
      double       fx[3], fy[3];
      nodal_forces(s.xx, s.yy, s.xy, x, y, fx, fy);
      for (unsigned int k = 0; k < 3; ++k)
        {
          f[2 * k]     = fx[k];
          f[2 * k + 1] = fy[k];
        }
    }
  } // namespace discrete
} // namespace tmfdem

#endif
