/**
 * Unit checks of ThermoelasticMaterial: the consistent tangent against a
 * central finite difference of the first Piola-Kirchhoff stress, P = J sigma
 * F^-T, the small-strain limit of the finite-strain law, zero stress under
 * rigid rotation and free thermal expansion, and the restrained-sheet
 * stresses of both 2D idealisations and the restrained 3D cube against their
 * closed forms, in 2D and 3D.
 */
#include <deal.II/base/symmetric_tensor.h>

#include <cmath>
#include <cstdio>
#include <tmfdem/continuum/thermoelastic_material.h>

using namespace tmfdem;

namespace
{
  int failures = 0;

  void
  expect(const bool condition, const char *what, const double value)
  {
    std::printf("%s: %s (%.3e)\n", condition ? "PASS" : "FAIL", what, value);
    failures += condition ? 0 : 1;
  }

  template <int dim>
  double
  max_abs(const Tensor<2, dim> &t)
  {
    double m = 0.;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        m = std::max(m, std::abs(t[i][j]));
    return m;
  }

  MaterialProperties
  table3_material()
  {
    MaterialProperties m;
    m.youngs_modulus        = 75.1e9;
    m.poisson_ratio         = 0.311;
    m.thermal_expansion     = 3e-6;
    m.reference_temperature = 20.;
    return m;
  }

  /** Every check for one dimension, idealisation and strain measure. */
  template <int dim>
  void
  check(const MaterialProperties                &properties,
        const MechanicsParameters::Idealisation  idealisation,
        const MechanicsParameters::StrainMeasure measure,
        const Tensor<2, dim>                    &grad_u,
        const double                             T)
  {
    const double E = properties.youngs_modulus, nu = properties.poisson_ratio,
                 alpha = properties.thermal_expansion;
    MechanicsParameters mechanics;
    mechanics.idealisation   = idealisation;
    mechanics.strain_measure = measure;
    const ThermoelasticMaterial<dim> material(properties, mechanics);
    const bool finite = measure == MechanicsParameters::StrainMeasure::finite;
    std::printf("--- %uD, %s, %s strain\n",
                dim,
                idealisation ==
                    MechanicsParameters::Idealisation::plane_stress ?
                  "plane stress" :
                idealisation ==
                    MechanicsParameters::Idealisation::plane_strain ?
                  "plane strain" :
                  "3D",
                finite ? "finite" : "small");

    // tangent against central differences
    const Tensor<4, dim> A     = material.tangent(grad_u, T);
    const double         h     = 1e-6;
    double               error = 0., scale = 0.;
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int l = 0; l < dim; ++l)
        {
          Tensor<2, dim> plus = grad_u, minus = grad_u;
          plus[k][l] += h;
          minus[k][l] -= h;
          const Tensor<2, dim> difference =
            (material.first_piola(plus, T) - material.first_piola(minus, T)) /
            (2. * h);
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              {
                error =
                  std::max(error, std::abs(difference[i][j] - A[i][j][k][l]));
                scale = std::max(scale, std::abs(A[i][j][k][l]));
              }
        }
    expect(error < 1e-7 * scale,
           "tangent = finite difference of P",
           error / scale);

    // major symmetry (hyperelastic)
    double asymmetry = 0.;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            asymmetry =
              std::max(asymmetry, std::abs(A[i][j][k][l] - A[k][l][i][j]));
    expect(asymmetry < 1e-12 * scale,
           "tangent has major symmetry",
           asymmetry / scale);

    // restrained sheet (2D) or cube (3D): grad u = 0; F_e = I / theta,
    // sigma = mu theta^dim (theta^-2 - 1) + lambda / 2 (theta^-dim -
    // theta^dim)
    const double         s   = material.in_plane_expansion() * (T - 20.);
    const double         lam = material.lambda(), mu = material.mu();
    const Tensor<2, dim> restrained = material.cauchy(Tensor<2, dim>(), T);
    const double         theta = 1. + s, theta_dim = std::pow(theta, dim);
    const double         expected = finite ?
                                      mu * theta_dim * (1. / (theta * theta) - 1.) +
                                0.5 * lam * (1. / theta_dim - theta_dim) :
                                      -(dim * lam + 2. * mu) * s;
    expect(std::abs(restrained[0][0] - expected) < 1e-12 * std::abs(expected) &&
             std::abs(restrained[dim - 1][dim - 1] - expected) <
               1e-12 * std::abs(expected) &&
             std::abs(restrained[0][1]) < 1e-9,
           "restrained stress = closed form",
           std::abs(restrained[0][0] - expected) / std::abs(expected));
    const double idealisation_formula =
      idealisation == MechanicsParameters::Idealisation::plane_stress ?
        -E * alpha * (T - 20.) / (1. - nu) :
        -E * alpha * (T - 20.) / (1. - 2. * nu);
    if (!finite)
      expect(std::abs(restrained[0][0] - idealisation_formula) <
               1e-12 * std::abs(idealisation_formula),
             "small strain: -E alpha dT/(1-nu) (plane stress) or /(1-2nu) "
             "(plane strain, 3D)",
             std::abs(restrained[0][0] / idealisation_formula - 1.));

    // free expansion: F = (1 + beta dT) I gives no stress
    Tensor<2, dim> free_expansion;
    for (unsigned int d = 0; d < dim; ++d)
      free_expansion[d][d] = s;
    expect(max_abs(material.cauchy(free_expansion, T)) < 1e-12 * E,
           "free thermal expansion is stress free",
           max_abs(material.cauchy(free_expansion, T)) / E);

    if (finite)
      {
        // P = J sigma F^-T
        const Tensor<2, dim> F = unit_symmetric_tensor<dim>() + grad_u;
        const Tensor<2, dim> P_from_sigma =
          determinant(F) * material.cauchy(grad_u, T) * transpose(invert(F));
        const double difference =
          max_abs(P_from_sigma - material.first_piola(grad_u, T));
        expect(difference < 1e-12 * max_abs(P_from_sigma),
               "P = J sigma F^-T",
               difference / max_abs(P_from_sigma));
        // rigid rotation by 90 degrees about z (in 3D then by 90 degrees
        // about x) at the reference temperature, and with free expansion
        Tensor<2, dim> R;
        R[0][1] = -1.;
        R[1][0] = 1.;
        if (dim == 3)
          {
            R[dim - 1][dim - 1] = 1.;
            Tensor<2, dim> Rx;
            Rx[0][0] = 1.;
            Rx[1][2] = -1.;
            Rx[2][1] = 1.;
            R        = Rx * R;
          }
        const Tensor<2, dim> rotation = R - unit_symmetric_tensor<dim>();
        expect(max_abs(material.cauchy(rotation, 20.)) < 1e-12 * E,
               "90 degree rotation is stress free",
               max_abs(material.cauchy(rotation, 20.)) / E);
        const Tensor<2, dim> rotated_expansion =
          theta * R - unit_symmetric_tensor<dim>();
        expect(max_abs(material.cauchy(rotated_expansion, T)) < 1e-12 * E,
               "rotated free expansion is stress free",
               max_abs(material.cauchy(rotated_expansion, T)) / E);
        // small-strain limit
        MechanicsParameters linear = mechanics;
        linear.strain_measure      = MechanicsParameters::StrainMeasure::small;
        const ThermoelasticMaterial<dim> small(properties, linear);
        const Tensor<2, dim>             tiny   = 1e-7 * grad_u;
        const double                     T_tiny = 20. + 0.01;
        const double                     limit =
          max_abs(material.cauchy(tiny, T_tiny) - small.cauchy(tiny, T_tiny));
        expect(limit < 1e-5 * max_abs(small.cauchy(tiny, T_tiny)),
               "finite -> small strain for small gradients",
               limit / max_abs(small.cauchy(tiny, T_tiny)));
      }
  }
} // namespace

int
main()
{
  const MaterialProperties properties = table3_material();
  const double T = 20. + 8000.; // alpha dT = 0.024 (plane stress, 3D)
  Tensor<2, 2> grad_u;
  grad_u[0][0] = 0.031;
  grad_u[0][1] = -0.12;
  grad_u[1][0] = 0.27;
  grad_u[1][1] = -0.045;
  Tensor<2, 3> grad_u_3d;
  const double values[3][3] = {{0.031, -0.12, 0.05},
                               {0.27, -0.045, -0.08},
                               {-0.03, 0.11, 0.062}};
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      grad_u_3d[i][j] = values[i][j];

  for (const auto measure : {MechanicsParameters::StrainMeasure::small,
                             MechanicsParameters::StrainMeasure::finite})
    {
      for (const auto idealisation :
           {MechanicsParameters::Idealisation::plane_stress,
            MechanicsParameters::Idealisation::plane_strain})
        check<2>(properties, idealisation, measure, grad_u, T);
      check<3>(properties,
               MechanicsParameters::Idealisation::solid_3d,
               measure,
               grad_u_3d,
               T);
    }
  std::printf(failures == 0 ? "all checks passed\n" : "%d checks failed\n",
              failures);
  return failures == 0 ? 0 : 1;
}
