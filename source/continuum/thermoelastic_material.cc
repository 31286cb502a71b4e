#include <deal.II/base/symmetric_tensor.h>

#include <cmath>
#include <limits>
#include <tmfdem/continuum/thermoelastic_material.h>

namespace tmfdem
{
  ThermoelasticMaterial::ThermoelasticMaterial(
    const MaterialProperties  &properties,
    const MechanicsParameters &mechanics)
    : strain_measure(mechanics.strain_measure)
    , idealisation(mechanics.idealisation)
    , youngs_modulus(properties.youngs_modulus)
    , poisson_ratio(properties.poisson_ratio)
    , alpha(properties.thermal_expansion)
    , reference_temperature(properties.reference_temperature)
  {
    const constitutive::LameConstants lame =
      constitutive::lame_constants(youngs_modulus, poisson_ratio, idealisation);
    shear_modulus = lame.mu;
    lambda_2d     = lame.lambda;
    beta = constitutive::in_plane_expansion(alpha, poisson_ratio, idealisation);
  }

  Tensor<2, 2>
  double_contract_right(const Tensor<4, 2> &A, const Tensor<2, 2> &G)
  {
    Tensor<2, 2> result;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = 0; l < 2; ++l)
            result[i][j] += A[i][j][k][l] * G[k][l];
    return result;
  }

  Tensor<2, 2>
  ThermoelasticMaterial::first_piola(const Tensor<2, 2> &grad_u,
                                     const double        temperature) const
  {
    const Tensor<2, 2> I = unit_symmetric_tensor<2>();
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      {
        const Tensor<2, 2> elastic_strain =
          0.5 * (grad_u + transpose(grad_u)) -
          beta * temperature_change(temperature) * I;
        return lambda_2d * trace(elastic_strain) * I +
               2. * shear_modulus * elastic_strain;
      }
    // P = theta [mu (F_e - F_e^-T) + lambda/2 (J_e^2 - 1) F_e^-T]
    const double       theta         = thermal_stretch(temperature);
    const Tensor<2, 2> F_e           = (I + grad_u) / theta;
    const double       J_e           = determinant(F_e);
    const Tensor<2, 2> F_e_inverse_T = transpose(invert(F_e));
    return theta * (shear_modulus * (F_e - F_e_inverse_T) +
                    0.5 * lambda_2d * (J_e * J_e - 1.) * F_e_inverse_T);
  }

  Tensor<4, 2>
  ThermoelasticMaterial::tangent(const Tensor<2, 2> &grad_u,
                                 const double        temperature) const
  {
    Tensor<4, 2> A;
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      {
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            for (unsigned int k = 0; k < 2; ++k)
              for (unsigned int l = 0; l < 2; ++l)
                A[i][j][k][l] =
                  lambda_2d * (i == j) * (k == l) +
                  shear_modulus * ((i == k) * (j == l) + (i == l) * (j == k));
        return A;
      }
    // P(F) = theta P_e(F / theta), so dP/dF = dP_e/dF_e (G = F_e):
    // A_iJkL = mu d_ik d_JL + (mu - lambda/2 (J^2 - 1)) G^-T_iL G^-T_kJ
    //          + lambda J^2 G^-T_iJ G^-T_kL
    const Tensor<2, 2> I = unit_symmetric_tensor<2>();
    const Tensor<2, 2> G = (I + grad_u) / thermal_stretch(temperature);
    const double       J = determinant(G);
    const Tensor<2, 2> H = transpose(invert(G));
    const double       c = shear_modulus - 0.5 * lambda_2d * (J * J - 1.);
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = 0; l < 2; ++l)
            A[i][j][k][l] = shear_modulus * (i == k) * (j == l) +
                            c * H[i][l] * H[k][j] +
                            lambda_2d * J * J * H[i][j] * H[k][l];
    return A;
  }

  Tensor<2, 2>
  ThermoelasticMaterial::cauchy(const Tensor<2, 2> &grad_u,
                                const double        temperature) const
  {
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      return first_piola(grad_u, temperature);
    // Eq. 44 on the elastic part, the core both layers share
    const Tensor<2, 2> I   = unit_symmetric_tensor<2>();
    const Tensor<2, 2> F_e = (I + grad_u) / thermal_stretch(temperature);
    const constitutive::Stress2 s =
      constitutive::elastic_stress(F_e[0][0],
                                   F_e[0][1],
                                   F_e[1][0],
                                   F_e[1][1],
                                   lame_constants());
    Tensor<2, 2> sigma;
    sigma[0][0] = s.xx;
    sigma[1][1] = s.yy;
    sigma[0][1] = s.xy;
    sigma[1][0] = s.xy;
    return sigma;
  }

  double
  ThermoelasticMaterial::out_of_plane_stress(
    const Tensor<2, 2> &in_plane_cauchy,
    const double        temperature) const
  {
    if (idealisation == MechanicsParameters::Idealisation::plane_stress)
      return 0.;
    if (strain_measure == MechanicsParameters::StrainMeasure::finite)
      return std::numeric_limits<double>::quiet_NaN();
    return poisson_ratio * trace(in_plane_cauchy) -
           youngs_modulus * alpha * temperature_change(temperature);
  }

  Tensor<2, 2>
  ThermoelasticMaterial::strain(const Tensor<2, 2> &grad_u) const
  {
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      return 0.5 * (grad_u + transpose(grad_u));
    return 0.5 * (grad_u + transpose(grad_u) + transpose(grad_u) * grad_u);
  }

  bool
  ThermoelasticMaterial::admissible(const Tensor<2, 2> &grad_u,
                                    const double        temperature) const
  {
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      return true;
    const Tensor<2, 2> I = unit_symmetric_tensor<2>();
    return thermal_stretch(temperature) > 0. && determinant(I + grad_u) > 0.;
  }
} // namespace tmfdem
