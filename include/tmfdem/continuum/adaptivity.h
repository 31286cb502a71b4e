/**
 * @file
 * Kelly-estimator marking shared by the continuum solvers: estimate the
 * error of a solution, mark cells by `Adaptive refinement/Strategy`, and keep
 * the levels between the initial mesh and Maximum level above it.
 */
#ifndef tmfdem_continuum_adaptivity_h
#define tmfdem_continuum_adaptivity_h

#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>

#include <tmfdem/base/parameters.h>

namespace tmfdem
{
  /**
   * Sets refine and coarsen flags on @p triangulation (p4est, quadrilaterals or
   * hexahedra) from the Kelly estimate of the ghosted @p solution, integrated
   * with QGauss(@p degree + 1) on faces; cells at @p coarse_level + Maximum
   * level are not refined, cells at @p coarse_level not coarsened.
   */
  template <int dim>
  void
  mark_cells_by_kelly(parallel::distributed::Triangulation<dim> &triangulation,
                      const Mapping<dim>                        &mapping,
                      const DoFHandler<dim>                     &dof_handler,
                      const TrilinosWrappers::MPI::Vector       &solution,
                      const unsigned int                         degree,
                      const AdaptivityParameters                &adaptivity,
                      const unsigned int                         coarse_level);
} // namespace tmfdem

#endif
