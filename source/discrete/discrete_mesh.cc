#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/discrete_mesh.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/mesh/cell_order.h>
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
      // ids without a subsection (or beyond them) are refused, naming the
      // cells and the bodies that use them
      const auto &read = parameters.sections_read;
      const bool  bodies_read =
        read.empty() ||
        std::find(read.begin(), read.end(), "Discrete bodies") != read.end();
      for (const auto id : report.material_ids)
        {
          std::string where =
            "cells of the " + source +
            (parameters.mesh.source == MeshParameters::Source::file ?
               "" :
               " (Mesh/Material id)");
          if (bodies_read)
            for (const auto &body :
                 parameters.get<DiscreteBodyParameters>().bodies)
              if (std::find(body.material_ids.begin(),
                            body.material_ids.end(),
                            id) != body.material_ids.end())
                where += " and by " + body.name + "/Material ids";
          parameters.materials.require_given(id, where);
        }
      if (report.n_quadrilaterals > 0)
        throw InputError(source +
                         " has quadrilaterals; the discrete layer needs "
                         "triangles (Mesh/Element type = triangles).");
      triangulation.refine_global(parameters.mesh.global_refinements);
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      std::vector<unsigned int> mesh_index;
      if (dm.hilbert_curve_numbering)
        mesh_index = order_cells_along_hilbert_curve(triangulation);
      dof_handler.reinit(triangulation);
      dof_handler.distribute_dofs(fe);
      model.build(dof_handler);
      if (!mesh_index.empty())
        model.mesh_index = mesh_index;

      // pre-existing fractures: joints on the given segments start broken
      const auto &cracks = dm.initial_cracks;
      for (unsigned int c = 0; c < cracks.size(); ++c)
        {
          const auto  &s  = cracks[c];
          const double dx = s[2] - s[0], dy = s[3] - s[1];
          const double length = std::hypot(dx, dy);
          unsigned int n_on   = 0;
          auto         on_segment =
            [&](const double x, const double y, const double tol) {
              const double t =
                ((x - s[0]) * dx + (y - s[1]) * dy) / (length * length);
              const double distance =
                std::abs((x - s[0]) * dy - (y - s[1]) * dx) / length;
              return distance <= tol && t >= -tol / length &&
                     t <= 1. + tol / length;
            };
          for (unsigned int j = 0; j < model.n_joints; ++j)
            {
              const unsigned int a0  = model.joint_nodes[4 * j];
              const unsigned int a1  = model.joint_nodes[4 * j + 1];
              const double       tol = 1e-6 * model.joint_length[j];
              if (length > 0. &&
                  on_segment(model.x_ref[a0], model.y_ref[a0], tol) &&
                  on_segment(model.x_ref[a1], model.y_ref[a1], tol))
                {
                  model.joint_status[j]     = JointStatus::mode_I;
                  model.joint_break_time[j] = parameters.time.start_time;
                  model.joint_damage[2 * j] = model.joint_damage[2 * j + 1] =
                    1.;
                  ++n_on;
                }
            }
          if (n_on == 0)
            throw InputError("Discrete mechanics/Initial cracks: no joint lies "
                             "on segment " +
                             std::to_string(c + 1) +
                             "; the mesh needs edges along it (gmsh: Line In "
                             "Surface).");
        }
    }

    void
    locate_monitors(const MonitorParameters      &monitors,
                    const DiscreteModel          &model,
                    std::vector<ReferenceSample> &probes,
                    std::vector<ReferenceSample> &line_points)
    {
      auto locate = [&](const std::string &name, const Point<3> &p) {
        ReferenceSample sample;
        sample.name = name;
        sample.x    = p[0];
        sample.y    = p[1];
        // of the elements that hold the point (on an edge or vertex,
        // several), the first in the mesh's order (DiscreteModel::mesh_index)
        bool found = false;
        for (unsigned int e = 0; e < model.n_elements; ++e)
          {
            if (found && model.mesh_index[e] > model.mesh_index[sample.element])
              continue;
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
                found            = true;
                sample.element   = e;
                sample.lambda[0] = l0;
                sample.lambda[1] = l1;
                sample.lambda[2] = l2;
              }
          }
        if (found)
          return sample;
        if (monitors.snap_to_nearest && model.n_elements > 0)
          {
            // the nearest point of the nearest element (reference mesh)
            double best = 1e300;
            for (unsigned int e = 0; e < model.n_elements; ++e)
              for (unsigned int k = 0; k < 3; ++k)
                {
                  const unsigned int a = 3 * e + k, b = 3 * e + (k + 1) % 3;
                  const double       ex = model.x_ref[b] - model.x_ref[a];
                  const double       ey = model.y_ref[b] - model.y_ref[a];
                  const double t = std::clamp(((p[0] - model.x_ref[a]) * ex +
                                               (p[1] - model.y_ref[a]) * ey) /
                                                (ex * ex + ey * ey),
                                              0.,
                                              1.);
                  const double d = std::hypot(model.x_ref[a] + t * ex - p[0],
                                              model.y_ref[a] + t * ey - p[1]);
                  if (d < best ||
                      (d == best &&
                       model.mesh_index[e] < model.mesh_index[sample.element]))
                    {
                      best             = d;
                      sample.element   = e;
                      sample.lambda[0] = sample.lambda[1] = sample.lambda[2] =
                        0.;
                      sample.lambda[k]           = 1. - t;
                      sample.lambda[(k + 1) % 3] = t;
                    }
                }
            return sample;
          }
        std::ostringstream where;
        where << "(" << p[0] << ", " << p[1] << ")";
        throw InputError("Monitors: point '" + name + "' at " + where.str() +
                         " lies outside the mesh (or set Monitors/Snap to "
                         "nearest element = true).");
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
