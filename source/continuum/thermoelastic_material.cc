#include <deal.II/base/symmetric_tensor.h>

#include <cmath>
#include <limits>
#include <tmfdem/continuum/thermoelastic_material.h>

namespace tmfdem
{
  template <int dim>
  ThermoelasticMaterial<dim>::ThermoelasticMaterial(
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
    lambda_       = lame.lambda;
    beta = constitutive::in_plane_expansion(alpha, poisson_ratio, idealisation);
  }

  template <int dim>
  Tensor<2, dim>
  double_contract_right(const Tensor<4, dim> &A, const Tensor<2, dim> &G)
  {
    Tensor<2, dim> result;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            result[i][j] += A[i][j][k][l] * G[k][l];
    return result;
  }

  template <int dim>
  Tensor<2, dim>
  ThermoelasticMaterial<dim>::first_piola(const Tensor<2, dim> &grad_u,
                                          const double temperature) const
  {
    const Tensor<2, dim> I = unit_symmetric_tensor<dim>();
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      {
        const Tensor<2, dim> elastic_strain =
          0.5 * (grad_u + transpose(grad_u)) -
          beta * temperature_change(temperature) * I;
        return lambda_ * trace(elastic_strain) * I +
               2. * shear_modulus * elastic_strain;
      }
    // P = theta^(dim-1) [mu (F_e - F_e^-T) + lambda/2 (J_e^2 - 1) F_e^-T]
    const double         theta         = thermal_stretch(temperature);
    const Tensor<2, dim> F_e           = (I + grad_u) / theta;
    const double         J_e           = determinant(F_e);
    const Tensor<2, dim> F_e_inverse_T = transpose(invert(F_e));
    const double         area_factor   = dim == 2 ? theta : theta * theta;
    return area_factor * (shear_modulus * (F_e - F_e_inverse_T) +
                          0.5 * lambda_ * (J_e * J_e - 1.) * F_e_inverse_T);
  }

  template <int dim>
  Tensor<4, dim>
  ThermoelasticMaterial<dim>::tangent(const Tensor<2, dim> &grad_u,
                                      const double          temperature) const
  {
    Tensor<4, dim> A;
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      {
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = 0; l < dim; ++l)
                A[i][j][k][l] =
                  lambda_ * (i == j) * (k == l) +
                  shear_modulus * ((i == k) * (j == l) + (i == l) * (j == k));
        return A;
      }
    // P(F) = theta^(dim-1) P_e(F / theta), so dP/dF = theta^(dim-2)
    // dP_e/dF_e (G = F_e):
    // A_iJkL = mu d_ik d_JL + (mu - lambda/2 (J^2 - 1)) G^-T_iL G^-T_kJ
    //          + lambda J^2 G^-T_iJ G^-T_kL
    const Tensor<2, dim> I     = unit_symmetric_tensor<dim>();
    const double         theta = thermal_stretch(temperature);
    const Tensor<2, dim> G     = (I + grad_u) / theta;
    const double         J     = determinant(G);
    const Tensor<2, dim> H     = transpose(invert(G));
    const double         c     = shear_modulus - 0.5 * lambda_ * (J * J - 1.);
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            A[i][j][k][l] = shear_modulus * (i == k) * (j == l) +
                            c * H[i][l] * H[k][j] +
                            lambda_ * J * J * H[i][j] * H[k][l];
    if (dim == 3)
      A *= theta;
    return A;
  }

  template <int dim>
  Tensor<2, dim>
  ThermoelasticMaterial<dim>::cauchy(const Tensor<2, dim> &grad_u,
                                     const double          temperature) const
  {
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      return first_piola(grad_u, temperature);
    // Eq. 44 on the elastic part, the core both layers share
    const Tensor<2, dim> I   = unit_symmetric_tensor<dim>();
    const Tensor<2, dim> F_e = (I + grad_u) / thermal_stretch(temperature);
    double               Fe[dim][dim], s[dim][dim];
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        Fe[i][j] = F_e[i][j];
    constitutive::elastic_stress<dim, double>(Fe, shear_modulus, lambda_, s);
    Tensor<2, dim> sigma;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        sigma[i][j] = s[i][j];
    return sigma;
  }

  template <int dim>
  double
  ThermoelasticMaterial<dim>::out_of_plane_stress(
    const Tensor<2, dim> &in_plane_cauchy,
    const double          temperature) const
  {
    if (idealisation == MechanicsParameters::Idealisation::plane_stress)
      return 0.;
    if (strain_measure == MechanicsParameters::StrainMeasure::finite)
      return std::numeric_limits<double>::quiet_NaN();
    return poisson_ratio * trace(in_plane_cauchy) -
           youngs_modulus * alpha * temperature_change(temperature);
  }

  template <int dim>
  Tensor<2, dim>
  ThermoelasticMaterial<dim>::strain(const Tensor<2, dim> &grad_u) const
  {
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      return 0.5 * (grad_u + transpose(grad_u));
    return 0.5 * (grad_u + transpose(grad_u) + transpose(grad_u) * grad_u);
  }

  template <int dim>
  bool
  ThermoelasticMaterial<dim>::admissible(const Tensor<2, dim> &grad_u,
                                         const double temperature) const
  {
    if (strain_measure == MechanicsParameters::StrainMeasure::small)
      return true;
    const Tensor<2, dim> I = unit_symmetric_tensor<dim>();
    return thermal_stretch(temperature) > 0. && determinant(I + grad_u) > 0.;
  }
  template class ThermoelasticMaterial<2>;
  template class ThermoelasticMaterial<3>;
  template Tensor<2, 2>
  double_contract_right(const Tensor<4, 2> &, const Tensor<2, 2> &);
  template Tensor<2, 3>
  double_contract_right(const Tensor<4, 3> &, const Tensor<2, 3> &);
} // namespace tmfdem
