/**
 * @file
 * Building the discrete layer's mesh from the prm file (generated or gmsh
 * meshes, triangles only, one MPI process), and locating monitor points in
 * the reference configuration.
 */
#ifndef tmfdem_discrete_discrete_mesh_h
#define tmfdem_discrete_discrete_mesh_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/grid/tria.h>

#include <mpi.h>
#include <string>
#include <tmfdem/base/parameters.h>
#include <tmfdem/discrete/discrete_model.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * Creates the output folder, the mesh of `Mesh` (checked), the DoFs of
     * @p fe (FE_SimplexDGP(1)) and the exploded @p model. Throws InputError
     * for quadrilateral meshes and for more than one MPI process.
     */
    void
    build_discrete_mesh(const Parameters       &parameters,
                        MPI_Comm                communicator,
                        Triangulation<2>       &triangulation,
                        DoFHandler<2>          &dof_handler,
                        const FiniteElement<2> &fe,
                        DiscreteModel          &model);

    /** A monitor point: its element and area coordinates in the reference
     *  configuration. */
    struct ReferenceSample
    {
      std::string  name;
      double       x = 0., y = 0.;
      unsigned int element   = 0;
      double       lambda[3] = {0., 0., 0.};
    };

    /** The probes and line points of `Monitors`, located in @p model's
     *  reference mesh; InputError naming a point outside it. */
    void
    locate_monitors(const MonitorParameters      &monitors,
                    const DiscreteModel          &model,
                    std::vector<ReferenceSample> &probes,
                    std::vector<ReferenceSample> &line_points);
  } // namespace discrete
} // namespace tmfdem

#endif
