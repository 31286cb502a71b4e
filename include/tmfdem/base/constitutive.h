/**
 * @file
 * The one thermoelastic constitutive core of tmfdem, shared by the continuum
 * layer (continuum/thermoelastic_material.h, deal.II tensors) and the
 * discrete layer (discrete/solid.h, the constant-strain triangle of the
 * explicit hot path): the 2D idealisation, the Lame constants of each
 * idealisation, the in-plane thermal stretch s of F_T = s I, and the Cauchy
 * stress of paper Eq. 44 on the elastic part F_e of F = F_T F_e, with its
 * strain energy. Derivation in doc/theory.md, chapter 3.
 *
 * Everything is header-only inline arithmetic on plain doubles, with no
 * allocation: the discrete layer calls it once per triangle per explicit
 * step. It lives in base/ because base/parameters.h parses the idealisation
 * into the enum declared here, and base/ depends on no model folder.
 *
 * The order of the floating-point operations is part of the contract: both
 * layers' results are bitwise those of the code this replaced
 * (scripts/results_neutral.py), so rewrite no expression here without
 * checking that.
 */
#ifndef tmfdem_base_constitutive_h
#define tmfdem_base_constitutive_h

#include <cmath>

namespace tmfdem
{
  namespace constitutive
  {
    /**
     * How the out-of-plane direction of the 2D model is treated (parameter
     * `Mechanics/Idealisation`, read by both layers).
     */
    enum class Idealisation
    {
      plane_stress, ///< sigma_zz = 0
      plane_strain, ///< eps_zz = 0
      solid_3d      ///< a 3D model: no idealisation, the 3D constants
    };

    /** Elastic constants of the in-plane law [Pa]. */
    struct LameConstants
    {
      double mu     = 0.; ///< shear modulus [Pa]
      double lambda = 0.; ///< Lame's first parameter of the idealisation [Pa]
    };

    /** Symmetric in-plane Cauchy stress {xx, yy, xy} [Pa], tension positive. */
    struct Stress2
    {
      double xx = 0, yy = 0, xy = 0;
    };

    /**
     * Lame constants of the in-plane law for @p idealisation, from Young's
     * modulus @p youngs_modulus [Pa] and Poisson's ratio @p poisson_ratio
     * [-]: mu = E / (2 (1 + nu)) in all; plane strain and a 3D solid take
     * lambda = E nu / ((1 + nu)(1 - 2 nu)), plane stress the reduced
     * lambda* = E nu / (1 - nu^2).
     */
    inline LameConstants
    lame_constants(const double       youngs_modulus,
                   const double       poisson_ratio,
                   const Idealisation idealisation)
    {
      LameConstants c;
      c.mu = youngs_modulus / (2. * (1. + poisson_ratio));
      if (idealisation != Idealisation::plane_stress)
        c.lambda = youngs_modulus * poisson_ratio /
                   ((1. + poisson_ratio) * (1. - 2. * poisson_ratio));
      else
        c.lambda =
          youngs_modulus * poisson_ratio / (1. - poisson_ratio * poisson_ratio);
      return c;
    }

    /**
     * In-plane thermal expansion coefficient beta [1/K] of the idealisation
     * for the (3D, isotropic) coefficient @p expansion_coefficient [1/K]:
     * alpha in plane stress and in a 3D solid, (1 + nu) alpha in plane
     * strain (the out-of-plane constraint eps_zz = 0 adds nu alpha dT in
     * plane; see doc/theory.md).
     */
    inline double
    in_plane_expansion(const double       expansion_coefficient,
                       const double       poisson_ratio,
                       const Idealisation idealisation)
    {
      return idealisation == Idealisation::plane_strain ?
               (1. + poisson_ratio) * expansion_coefficient :
               expansion_coefficient;
    }

    /**
     * In-plane thermal stretch s = 1 + beta dT [-] of F_T = s I for a
     * temperature change @p delta_T [K], beta from in_plane_expansion().
     */
    inline double
    thermal_stretch(const double       expansion_coefficient,
                    const double       poisson_ratio,
                    const double       delta_T,
                    const Idealisation idealisation)
    {
      return 1. + in_plane_expansion(expansion_coefficient,
                                     poisson_ratio,
                                     idealisation) *
                    delta_T;
    }

    /** det A of a dim x dim matrix (rows first) [-]. */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline Number
    determinant(const Number (&A)[dim][dim])
    {
      static_assert(dim == 2 || dim == 3, "2D or 3D");
      if constexpr (dim == 2)
        return A[0][0] * A[1][1] - A[0][1] * A[1][0];
      else
        return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
               A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
               A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    }

    /**
     * Cauchy stress of paper Eq. 44 [Pa] on the elastic deformation gradient
     * @p Fe [-] (F_e = F / s, rows first), in 2D or 3D:
     * sigma = mu / J (B - I) + lambda / 2 (J - 1 / J) I with J = det F_e and
     * B = F_e F_e^T, written into @p sigma (symmetric, all entries set).
     * Reduces to 2 mu eps + lambda tr(eps) I for small strain. Lame
     * constants @p mu, @p lambda [Pa]. @p Number is double or a vector of
     * doubles (one element per lane, discrete/element_kernel.h): the one
     * body of the formula for the continuum layer in 2D and 3D, the
     * discrete layer's element loop and its vector batches.
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    elastic_stress(const Number (&Fe)[dim][dim],
                   const Number mu,
                   const Number lambda,
                   Number (&sigma)[dim][dim])
    {
      const Number J         = determinant<dim>(Fe);
      const Number inverse_J = 1. / J;
      const Number mu_J      = mu * inverse_J;
      const Number vol       = 0.5 * lambda * (J - inverse_J);
      for (int i = 0; i < dim; ++i)
        for (int j = i; j < dim; ++j)
          {
            Number b_ij = Fe[i][0] * Fe[j][0];
            for (int k = 1; k < dim; ++k)
              b_ij = b_ij + Fe[i][k] * Fe[j][k];
            if (i == j)
              sigma[i][i] = mu_J * (b_ij - 1.) + vol;
            else
              {
                sigma[i][j] = mu_J * b_ij;
                sigma[j][i] = sigma[i][j];
              }
          }
    }

    /**
     * The 2D stress of elastic_stress() on the components fe00, fe01, fe10,
     * fe11 of F_e, written into @p sxx, @p syy, @p sxy [Pa].
     */
    template <typename Number>
    __attribute__((always_inline)) inline void
    elastic_stress(const Number fe00,
                   const Number fe01,
                   const Number fe10,
                   const Number fe11,
                   const Number mu,
                   const Number lambda,
                   Number      &sxx,
                   Number      &syy,
                   Number      &sxy)
    {
      const Number Fe[2][2] = {{fe00, fe01}, {fe10, fe11}};
      Number       sigma[2][2];
      elastic_stress<2>(Fe, mu, lambda, sigma);
      sxx = sigma[0][0];
      syy = sigma[1][1];
      sxy = sigma[0][1];
    }

    /** The same for doubles, as a Stress2 [Pa]. */
    inline Stress2
    elastic_stress(const double         fe00,
                   const double         fe01,
                   const double         fe10,
                   const double         fe11,
                   const LameConstants &lame)
    {
      Stress2 s;
      elastic_stress(fe00,
                     fe01,
                     fe10,
                     fe11,
                     lame.mu,
                     lame.lambda,
                     s.xx,
                     s.yy,
                     s.xy);
      return s;
    }

    /**
     * Strain energy per unit area (2D) or volume (3D) of the stress-free
     * (intermediate) configuration [J/m^2, J/m^3] whose derivative is
     * Eq. 44, for the elastic deformation gradient @p Fe (rows first) [-]:
     * psi = mu/2 (tr B - dim) - mu ln J + lambda/4 (J^2 - 1 - 2 ln J).
     */
    template <int dim>
    inline double
    strain_energy_density(const double (&Fe)[dim][dim],
                          const LameConstants &lame)
    {
      const double J       = determinant<dim>(Fe);
      double       trace_B = 0.;
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j)
          trace_B += Fe[i][j] * Fe[i][j];
      const double log_J = std::log(J);
      return 0.5 * lame.mu * (trace_B - dim) - lame.mu * log_J +
             0.25 * lame.lambda * (J * J - 1. - 2. * log_J);
    }

    /** The same in 2D for F_e = [fe00, fe01; fe10, fe11] [-]. */
    inline double
    strain_energy_density(const double         fe00,
                          const double         fe01,
                          const double         fe10,
                          const double         fe11,
                          const LameConstants &lame)
    {
      const double Fe[2][2] = {{fe00, fe01}, {fe10, fe11}};
      return strain_energy_density<2>(Fe, lame);
    }
  } // namespace constitutive
} // namespace tmfdem

#endif
