#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/numerics/error_estimator.h>

#include <tmfdem/continuum/adaptivity.h>

namespace tmfdem
{
  void
  mark_cells_by_kelly(parallel::distributed::Triangulation<2> &triangulation,
                      const Mapping<2>                        &mapping,
                      const DoFHandler<2>                     &dof_handler,
                      const TrilinosWrappers::MPI::Vector     &solution,
                      const unsigned int                       degree,
                      const AdaptivityParameters              &adaptivity,
                      const unsigned int                       coarse_level)
  {
    Vector<float> estimated_error(triangulation.n_active_cells());
    KellyErrorEstimator<2>::estimate(mapping,
                                     dof_handler,
                                     QGauss<1>(degree + 1),
                                     {},
                                     solution,
                                     estimated_error);
    if (adaptivity.strategy == "fixed fraction")
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_fraction(
        triangulation,
        estimated_error,
        adaptivity.refine_fraction,
        adaptivity.coarsen_fraction);
    else
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
        triangulation,
        estimated_error,
        adaptivity.refine_fraction,
        adaptivity.coarsen_fraction);
    const unsigned int max_level = coarse_level + adaptivity.max_level;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (cell->level() >= static_cast<int>(max_level))
          cell->clear_refine_flag();
        if (cell->level() <= static_cast<int>(coarse_level))
          cell->clear_coarsen_flag();
      }
  }
} // namespace tmfdem
