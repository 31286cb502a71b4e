/**
 * @file
 * The thermoelastic constitutive law of tmfdem, small and finite strain, in
 * 2D (plane stress, plane strain) and 3D: stresses and consistent tangents as
 * functions of the displacement gradient and the temperature change, on
 * deal.II tensors for the continuum solver. The Lame constants, the
 * thermal stretch and the Cauchy stress of Eq. 44 on F_e come from the
 * constitutive core both layers share (base/constitutive.h); this class
 * adds the small-strain law, the first Piola-Kirchhoff stress and its
 * tangent. Derivation in doc/theory.md, chapter 3.
 */
#ifndef tmfdem_continuum_thermoelastic_material_h
#define tmfdem_continuum_thermoelastic_material_h

#include <deal.II/base/tensor.h>

#include <tmfdem/base/constitutive.h>
#include <tmfdem/base/parameters.h>

namespace tmfdem
{
  /**
   * Thermoelastic material of one material id in @p dim dimensions, in the
   * idealisation chosen in `Mechanics/Idealisation` (3D in 3D).
   *
   * Constants: mu = E / (2 (1 + nu)) always; lambda = E nu / ((1 + nu)(1 -
   * 2 nu)) in plane strain and 3D, lambda = E nu / (1 - nu^2) in plane
   * stress. Thermal expansion coefficient beta = alpha (plane stress, 3D) or
   * (1 + nu) alpha (plane strain, from eps_zz = 0).
   *
   * Small strain: sigma = lambda tr(eps - beta dT I) I + 2 mu (eps - beta dT
   * I), eps = sym(grad u).
   *
   * Finite strain: F = I + grad u = F_T F_e with F_T = (1 + beta dT) I; the
   * Cauchy stress is the paper's Eq. 44 on the elastic part,
   * sigma = mu / J_e (B_e - I) + lambda / 2 (J_e - 1 / J_e) I, with J_e =
   * det F_e and B_e = F_e F_e^T (dim x dim). Its first Piola-Kirchhoff
   * stress is P = J sigma F^-T = s^(dim-1) [mu (F_e - F_e^-T) + lambda / 2
   * (J_e^2 - 1) F_e^-T], s = 1 + beta dT, hyperelastic with a symmetric
   * tangent dP/dF = s^(dim-2) dP_e/dF_e.
   *
   * Units: stresses and moduli in Pa, temperatures in C, gradients
   * dimensionless.
   */
  template <int dim>
  class ThermoelasticMaterial
  {
  public:
    /** The constants of @p properties in the idealisation of @p mechanics. */
    ThermoelasticMaterial(const MaterialProperties  &properties,
                          const MechanicsParameters &mechanics);

    /** Lame's first parameter of the idealisation [Pa]. */
    double
    lambda() const
    {
      return lambda_;
    }
    /** Shear modulus [Pa]. */
    double
    mu() const
    {
      return shear_modulus;
    }
    /** Both Lame constants of the idealisation [Pa]. */
    constitutive::LameConstants
    lame_constants() const
    {
      return {shear_modulus, lambda_};
    }
    /** Thermal expansion coefficient beta of the idealisation [1/K]. */
    double
    in_plane_expansion() const
    {
      return beta;
    }
    /** Temperature change dT = T - T_ref for temperature @p T [C]. */
    double
    temperature_change(const double temperature) const
    {
      return temperature - reference_temperature;
    }
    /** Thermal stretch s = 1 + beta dT [-] (constitutive::thermal_stretch()).
     */
    double
    thermal_stretch(const double temperature) const
    {
      return constitutive::thermal_stretch(alpha,
                                           poisson_ratio,
                                           temperature_change(temperature),
                                           idealisation);
    }

    /**
     * First Piola-Kirchhoff stress P [Pa] (in small strain: the Cauchy
     * stress) for displacement gradient @p grad_u and temperature @p T [C].
     */
    Tensor<2, dim>
    first_piola(const Tensor<2, dim> &grad_u, const double temperature) const;

    /** The tangent dP/d(grad u) [Pa], A_{iJkL} = dP_{iJ}/dF_{kL}. */
    Tensor<4, dim>
    tangent(const Tensor<2, dim> &grad_u, const double temperature) const;

    /** Cauchy stress sigma [Pa] (in 2D the in-plane part), tension
     *  positive. */
    Tensor<2, dim>
    cauchy(const Tensor<2, dim> &grad_u, const double temperature) const;

    /**
     * Out-of-plane stress sigma_zz [Pa]: 0 in plane stress; in small-strain
     * plane strain nu (sigma_xx + sigma_yy) - E alpha dT (eps_zz = 0). For
     * finite-strain plane strain the 2D model of Eq. 44 does not define it:
     * NaN. 2D only.
     */
    double
    out_of_plane_stress(const Tensor<2, dim> &in_plane_cauchy,
                        const double          temperature) const;

    /**
     * Strain [-]: eps = sym(grad u) in small strain, the Green-Lagrange
     * strain E = (F^T F - I) / 2 in finite strain.
     */
    Tensor<2, dim>
    strain(const Tensor<2, dim> &grad_u) const;

    /** Does @p grad_u with @p T give an admissible state (J_e > 0)? */
    bool
    admissible(const Tensor<2, dim> &grad_u, const double temperature) const;

  private:
    MechanicsParameters::StrainMeasure strain_measure;
    MechanicsParameters::Idealisation  idealisation;
    double youngs_modulus, poisson_ratio, alpha, reference_temperature;
    double lambda_, shear_modulus, beta;
  };

  /** A : G, the double contraction (A : G)_{ij} = A_{ijkl} G_{kl}. */
  template <int dim>
  Tensor<2, dim>
  double_contract_right(const Tensor<4, dim> &A, const Tensor<2, dim> &G);
} // namespace tmfdem

#endif
