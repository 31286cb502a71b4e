#include <deal.II/base/mpi.h>

#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/discrete_mesh.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/mesh/mesh_checks.h>
#include <tmfdem/mesh/mesh_generator.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    build_discrete_mesh(const Parameters       &parameters,
                        MPI_Comm                communicator,
                        Triangulation<2>       &triangulation,
                        DoFHandler<2>          &dof_handler,
                        const FiniteElement<2> &fe,
                        DiscreteModel          &model)
    {
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        throw InputError("the discrete layer runs on one MPI process with "
                         "threads (Discrete mechanics/Threads); run it "
                         "without mpirun -np > 1.");
      create_output_folder(parameters.output.directory, communicator);
      create_coarse_mesh(parameters.mesh,
                         parameters.output.directory,
                         triangulation,
                         communicator);
      const std::string source =
        parameters.mesh.source == MeshParameters::Source::file ?
          "mesh file '" + parameters.mesh.file_name + "'" :
          "generated mesh";
      const MeshReport report =
        check_mesh(triangulation,
                   source,
                   domain_area(parameters.mesh),
                   parameters.mesh.source == MeshParameters::Source::annulus ||
                     parameters.mesh.source == MeshParameters::Source::disc);
      if (report.n_quadrilaterals > 0)
        throw InputError(source +
                         " has quadrilaterals; the discrete layer needs "
                         "triangles (Mesh/Element type = triangles).");
      triangulation.refine_global(parameters.mesh.global_refinements);
      dof_handler.reinit(triangulation);
      dof_handler.distribute_dofs(fe);
      model.build(dof_handler);
    }

    void
    locate_monitors(const MonitorParameters      &monitors,
                    const DiscreteModel          &model,
                    std::vector<ReferenceSample> &probes,
                    std::vector<ReferenceSample> &line_points)
    {
      auto locate = [&](const std::string &name, const Point<2> &p) {
        ReferenceSample sample;
        sample.name = name;
        sample.x    = p[0];
        sample.y    = p[1];
        for (unsigned int e = 0; e < model.n_elements; ++e)
          {
            const double *xr = &model.x_ref[3 * e], *yr = &model.y_ref[3 * e];
            const double  det = (yr[1] - yr[2]) * (xr[0] - xr[2]) +
                               (xr[2] - xr[1]) * (yr[0] - yr[2]);
            const double l0 = ((yr[1] - yr[2]) * (p[0] - xr[2]) +
                               (xr[2] - xr[1]) * (p[1] - yr[2])) /
                              det;
            const double l1 = ((yr[2] - yr[0]) * (p[0] - xr[2]) +
                               (xr[0] - xr[2]) * (p[1] - yr[2])) /
                              det;
            const double l2  = 1. - l0 - l1;
            const double tol = -1e-10;
            if (l0 >= tol && l1 >= tol && l2 >= tol)
              {
                sample.element   = e;
                sample.lambda[0] = l0;
                sample.lambda[1] = l1;
                sample.lambda[2] = l2;
                return sample;
              }
          }
        std::ostringstream where;
        where << "(" << p[0] << ", " << p[1] << ")";
        throw InputError("Monitors: point '" + name + "' at " + where.str() +
                         " lies outside the mesh.");
      };
      probes.clear();
      line_points.clear();
      for (const auto &probe : monitors.probes)
        probes.push_back(locate(probe.name, probe.location));
      for (const auto &line : monitors.lines)
        for (unsigned int i = 0; i < line.n_points; ++i)
          {
            const double s =
              line.n_points > 1 ? double(i) / (line.n_points - 1) : 0.;
            line_points.push_back(
              locate(line.name, line.start + s * (line.end - line.start)));
          }
    }
  } // namespace discrete
} // namespace tmfdem
