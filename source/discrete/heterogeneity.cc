#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <tmfdem/discrete/heterogeneity.h>

namespace tmfdem
{
  namespace discrete
  {
    std::vector<double>
    random_strength_factors(const DiscreteMechanicsParameters &dm,
                            const DiscreteModel               &model)
    {
      std::vector<double> factor(model.n_joints, 1.);
      if (dm.heterogeneity == DiscreteMechanicsParameters::Heterogeneity::none)
        return factor;
      // (mesh index of the element, its edge) of each joint's first side
      std::vector<std::pair<std::uint64_t, unsigned int>> order(model.n_joints);
      const unsigned int faces = model.nodes_per_element();
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int k = 0; k < faces; ++k)
          {
            const int code = model.edge_joint[faces * e + k];
            if (code < 0)
              continue;
            const unsigned int  j = code / 2;
            const std::uint64_t key =
              faces * std::uint64_t(model.mesh_index[e]) + k;
            const unsigned int other =
              model.joint_elements[2 * j + 1 - code % 2];
            if (model.mesh_index[e] < model.mesh_index[other])
              order[j] = {key, j};
          }
      std::sort(order.begin(), order.end());
      std::mt19937_64 generator(dm.random_seed);
      const double    m = dm.weibull_modulus;
      for (const auto &[key, j] : order)
        if (dm.heterogeneity ==
            DiscreteMechanicsParameters::Heterogeneity::weibull)
          {
            // Weibull with mean 1: scale = 1 / Gamma(1 + 1/m)
            std::weibull_distribution<double> weibull(m,
                                                      1. / std::tgamma(1. +
                                                                       1. / m));
            factor[j] = weibull(generator);
          }
        else
          {
            std::normal_distribution<double> normal(
              1.,
              dm.coefficient_of_variation);
            factor[j] = std::max(0.01, normal(generator));
          }
      return factor;
    }

    std::vector<double>
    random_expansion_factors(const DiscreteMechanicsParameters &dm,
                             const DiscreteModel               &model)
    {
      if (dm.expansion_heterogeneity ==
          DiscreteMechanicsParameters::ExpansionHeterogeneity::none)
        return {};
      // the elements in the mesh's order
      std::vector<unsigned int> order(model.n_elements);
      std::iota(order.begin(), order.end(), 0u);
      std::sort(order.begin(),
                order.end(),
                [&model](const unsigned int a, const unsigned int b) {
                  return model.mesh_index[a] < model.mesh_index[b];
                });
      // a sequence of its own: the strengths' field stays the same
      // whether this one is drawn or not
      std::seed_seq   seed{std::uint64_t(dm.random_seed), std::uint64_t(2)};
      std::mt19937_64 generator(seed);
      std::normal_distribution<double> normal(
        1.,
        dm.expansion_coefficient_of_variation);
      std::vector<double> factor(model.n_elements, 1.);
      for (const unsigned int e : order)
        factor[e] = std::max(0., normal(generator));
      return factor;
    }
  } // namespace discrete
} // namespace tmfdem
