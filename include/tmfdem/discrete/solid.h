/**
 * @file
 * The constant-strain triangle at finite strain (paper Sec. 2, 4.1-4.2 with
 * the corrections of the theory manual): deformation gradient from the
 * current and initial element bases, the multiplicative thermal split
 * F = F_T F_e with F_T = s I, the compressible neo-Hookean-type Cauchy
 * stress of Eq. 44 evaluated with the ELASTIC part F_e, and the viscous
 * stress 2 eta D with D = sym(dF/dt F^-1) (Eqs. 45-46).
 *
 * Everything here is plain inline arithmetic on doubles: these functions run
 * once per triangle per explicit step.
 */
#ifndef tmfdem_discrete_solid_h
#define tmfdem_discrete_solid_h

#include <cmath>

namespace tmfdem
{
  namespace discrete
  {
    /** A 2x2 matrix stored row-major: {a00, a01, a10, a11}. */
    struct Matrix2
    {
      double a00 = 0, a01 = 0, a10 = 0, a11 = 0;
    };

    /** Symmetric 2D stress {xx, yy, xy} [Pa], tension positive. */
    struct Stress2
    {
      double xx = 0, yy = 0, xy = 0;
    };

    /** Elastic constants of the 2D idealisation [Pa]. */
    struct LameConstants
    {
      double mu     = 0.;
      double lambda = 0.;
    };

    /** How the out-of-plane direction is treated. */
    enum class Idealisation
    {
      plane_stress,
      plane_strain
    };

    /**
     * Lame constants of the in-plane law for @p idealisation: plane strain
     * takes lambda = E nu / ((1+nu)(1-2nu)); plane stress the reduced
     * lambda* = E nu / (1 - nu^2). mu = E / (2 (1+nu)) in both.
     */
    inline LameConstants
    lame_constants(const double       youngs_modulus,
                   const double       poisson_ratio,
                   const Idealisation idealisation)
    {
      LameConstants c;
      c.mu = youngs_modulus / (2. * (1. + poisson_ratio));
      if (idealisation == Idealisation::plane_strain)
        c.lambda = youngs_modulus * poisson_ratio /
                   ((1. + poisson_ratio) * (1. - 2. * poisson_ratio));
      else
        c.lambda =
          youngs_modulus * poisson_ratio / (1. - poisson_ratio * poisson_ratio);
      return c;
    }

    /**
     * In-plane thermal stretch s of F_T = s I for a temperature change
     * @p delta_T [K]: 1 + alpha dT in plane stress, 1 + (1+nu) alpha dT in
     * plane strain (the out-of-plane constraint eps_zz = 0 adds nu alpha dT
     * in plane; see doc/theory.md).
     */
    inline double
    thermal_stretch(const double       expansion_coefficient,
                    const double       poisson_ratio,
                    const double       delta_T,
                    const Idealisation idealisation)
    {
      return idealisation == Idealisation::plane_strain ?
               1. + (1. + poisson_ratio) * expansion_coefficient * delta_T :
               1. + expansion_coefficient * delta_T;
    }

    /** Determinant. */
    inline double
    determinant(const Matrix2 &m)
    {
      return m.a00 * m.a11 - m.a01 * m.a10;
    }

    /** Inverse (the caller guarantees det != 0). */
    inline Matrix2
    inverse(const Matrix2 &m)
    {
      const double inv_det = 1. / determinant(m);
      return {m.a11 * inv_det,
              -m.a01 * inv_det,
              -m.a10 * inv_det,
              m.a00 * inv_det};
    }

    /** Product a b. */
    inline Matrix2
    multiply(const Matrix2 &a, const Matrix2 &b)
    {
      return {a.a00 * b.a00 + a.a01 * b.a10,
              a.a00 * b.a01 + a.a01 * b.a11,
              a.a10 * b.a00 + a.a11 * b.a10,
              a.a10 * b.a01 + a.a11 * b.a11};
    }

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
      return {x1 - x0, x2 - x0, y1 - y0, y2 - y0};
    }

    /**
     * Cauchy stress of paper Eq. 44 on the elastic deformation gradient
     * @p Fe [Pa]: sigma = mu/J (B - I) + lambda/2 (J - 1/J) I with
     * J = det Fe, B = Fe Fe^T. Reduces to 2 mu eps + lambda tr(eps) I for
     * small strain.
     */
    inline Stress2
    elastic_stress(const Matrix2 &Fe, const LameConstants &lame)
    {
      const double J    = determinant(Fe);
      const double b_xx = Fe.a00 * Fe.a00 + Fe.a01 * Fe.a01;
      const double b_yy = Fe.a10 * Fe.a10 + Fe.a11 * Fe.a11;
      const double b_xy = Fe.a00 * Fe.a10 + Fe.a01 * Fe.a11;
      const double mu_J = lame.mu / J;
      const double vol  = 0.5 * lame.lambda * (J - 1. / J);
      return {mu_J * (b_xx - 1.) + vol, mu_J * (b_yy - 1.) + vol, mu_J * b_xy};
    }

    /**
     * Strain energy per unit area of the stress-free (intermediate)
     * configuration [J/m^2] whose derivative is Eq. 44:
     * psi = mu/2 (tr B - 2) - mu ln J + lambda/4 (J^2 - 1 - 2 ln J).
     */
    inline double
    strain_energy_density(const Matrix2 &Fe, const LameConstants &lame)
    {
      const double J = determinant(Fe);
      const double trace_B =
        Fe.a00 * Fe.a00 + Fe.a01 * Fe.a01 + Fe.a10 * Fe.a10 + Fe.a11 * Fe.a11;
      const double log_J = std::log(J);
      return 0.5 * lame.mu * (trace_B - 2.) - lame.mu * log_J +
             0.25 * lame.lambda * (J * J - 1. - 2. * log_J);
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
