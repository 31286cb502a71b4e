#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/numerics/error_estimator.h>

#include <tmfdem/continuum/adaptivity.h>

namespace tmfdem
{
  template <int dim>
  void
  mark_cells_by_kelly(parallel::distributed::Triangulation<dim> &triangulation,
                      const Mapping<dim>                        &mapping,
                      const DoFHandler<dim>                     &dof_handler,
                      const TrilinosWrappers::MPI::Vector       &solution,
                      const unsigned int                         degree,
                      const AdaptivityParameters                &adaptivity,
                      const unsigned int                         coarse_level)
  {
    Vector<float> estimated_error(triangulation.n_active_cells());
    KellyErrorEstimator<dim>::estimate(mapping,
                                       dof_handler,
                                       QGauss<dim - 1>(degree + 1),
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

  template void
  mark_cells_by_kelly<2>(parallel::distributed::Triangulation<2> &,
                         const Mapping<2> &,
                         const DoFHandler<2> &,
                         const TrilinosWrappers::MPI::Vector &,
                         const unsigned int,
                         const AdaptivityParameters &,
                         const unsigned int);
  template void
  mark_cells_by_kelly<3>(parallel::distributed::Triangulation<3> &,
                         const Mapping<3> &,
                         const DoFHandler<3> &,
                         const TrilinosWrappers::MPI::Vector &,
                         const unsigned int,
                         const AdaptivityParameters &,
                         const unsigned int);
} // namespace tmfdem
