/**
 * @file
 * Random fields of material properties in the discrete layer (subsection
 * Discrete mechanics): the joints' tensile strength and cohesion
 * (Heterogeneity) and the triangles' thermal expansion coefficient
 * (Expansion heterogeneity). Each field is drawn from Random seed, each
 * from its own sequence, in an order fixed by the mesh (DiscreteModel::
 * mesh_index), so the same seed gives the same field whatever the
 * numbering of the triangles, the number of ranks or threads, and whether
 * the other field is drawn.
 */
#ifndef tmfdem_discrete_heterogeneity_h
#define tmfdem_discrete_heterogeneity_h

#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * Factor [-] of each joint's tensile strength and cohesion
     * (Heterogeneity: Weibull of mean 1 and modulus Weibull modulus, or
     * normal of mean 1 and Coefficient of variation truncated at 0.01; 1
     * everywhere for none), one per joint of @p model, drawn in the mesh's
     * order of the joints (by the mesh index of the joint's first element
     * and its edge there).
     */
    std::vector<double>
    random_strength_factors(const DiscreteMechanicsParameters &dm,
                            const DiscreteModel               &model);

    /**
     * Factor [-] of each triangle's thermal expansion coefficient
     * (Expansion heterogeneity: normal of mean 1 and standard deviation
     * Expansion coefficient of variation, truncated at 0), one per element
     * of @p model, drawn in the mesh's order of the triangles; empty for
     * none (1 everywhere).
     */
    std::vector<double>
    random_expansion_factors(const DiscreteMechanicsParameters &dm,
                             const DiscreteModel               &model);
  } // namespace discrete
} // namespace tmfdem

#endif
