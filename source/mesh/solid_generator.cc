/**
 * @file
 * The 3D coarse meshes of Mesh/Dimension = 3: a box, a ball and a spherical
 * shell of hexahedra (or tetrahedra split from them), and gmsh .msh files
 * with tetrahedra or hexahedra.
 */
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/manifold_lib.h>

#include <algorithm>
#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/mesh/mesh_generator.h>

namespace tmfdem
{
  namespace
  {
    /** Manifold id of the cells and faces that follow a sphere. */
    constexpr types::manifold_id sphere_manifold_id = 1;

    /** Longest edge of the active cells [m]. */
    double
    longest_edge(const Triangulation<3> &triangulation)
    {
      double longest = 0.;
      for (const auto &cell : triangulation.active_cell_iterators())
        for (unsigned int l = 0; l < cell->n_lines(); ++l)
          longest = std::max(longest, cell->line(l)->diameter());
      return longest;
    }

    /** Refines @p triangulation globally until no edge is longer than
     *  1.01 @p h (at most 8 times), then makes the result its coarse
     *  level (p4est and the simplex conversion need a flat mesh). */
    void
    refine_to_size_and_flatten(Triangulation<3> &triangulation, const double h)
    {
      for (unsigned int n = 0; n < 8 && longest_edge(triangulation) > 1.01 * h;
           ++n)
        triangulation.refine_global(1);
      if (triangulation.n_levels() > 1)
        {
          Triangulation<3> flat;
          GridGenerator::flatten_triangulation(triangulation, flat);
          triangulation.clear();
          triangulation.copy_triangulation(flat);
        }
      // the generator's manifolds stay behind; the caller attaches its own
      triangulation.reset_all_manifolds();
      triangulation.set_all_manifold_ids(numbers::flat_manifold_id);
    }

    /** Boundary ids of the box (0/1 x = x0/x1, 2/3 y, 4/5 z), the ball
     *  (0) and the shell (0 inner, 1 outer), from where each boundary
     *  face lies: flattening and the simplex conversion keep no ids. */
    void
    set_boundary_ids(const MeshParameters &parameters,
                     Triangulation<3>     &triangulation)
    {
      using Source       = MeshParameters::Source;
      const Point<3> &lo = parameters.lower_left, &hi = parameters.upper_right;
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              const Point<3> c = face->center();
              if (parameters.source == Source::box)
                {
                  // the coordinate whose plane the face lies in
                  unsigned int best_id = 0;
                  double       best    = 1e300;
                  for (unsigned int d = 0; d < 3; ++d)
                    for (unsigned int side = 0; side < 2; ++side)
                      {
                        const double distance =
                          std::abs(c[d] - (side == 0 ? lo[d] : hi[d]));
                        if (distance < best)
                          {
                            best    = distance;
                            best_id = 2 * d + side;
                          }
                      }
                  face->set_boundary_id(best_id);
                }
              else if (parameters.source == Source::spherical_shell)
                face->set_boundary_id(c.distance(parameters.center) <
                                          0.5 * (parameters.inner_radius +
                                                 parameters.outer_radius) ?
                                        0 :
                                        1);
              else
                face->set_boundary_id(0);
            }
    }
  } // namespace

  double
  domain_volume(const MeshParameters &p)
  {
    using Source = MeshParameters::Source;
    switch (p.source)
      {
        case Source::box:
          return (p.upper_right[0] - p.lower_left[0]) *
                 (p.upper_right[1] - p.lower_left[1]) *
                 (p.upper_right[2] - p.lower_left[2]);
        case Source::ball:
          return 4. / 3. * numbers::PI * std::pow(p.outer_radius, 3);
        case Source::spherical_shell:
          return 4. / 3. * numbers::PI *
                 (std::pow(p.outer_radius, 3) - std::pow(p.inner_radius, 3));
        default:
          return p.expected_area;
      }
  }

  void
  create_coarse_mesh(const MeshParameters &parameters,
                     const std::string    &work_folder,
                     Triangulation<3>     &triangulation,
                     MPI_Comm /*communicator*/)
  {
    using Source = MeshParameters::Source;
    (void)work_folder;
    if (parameters.source == Source::file)
      {
        const std::string &name = parameters.file_name;
        if (name.size() > 4 && name.substr(name.size() - 4) == ".geo")
          throw InputError("Mesh/File name = '" + name +
                           "': tmfdem meshes .geo scripts in 2D only; for "
                           "Mesh/Dimension = 3 mesh it with gmsh (gmsh -3 " +
                           "file.geo -format msh22) and give the .msh file.");
        read_gmsh_file(name, triangulation);
        return;
      }

    const double h = parameters.element_size;
    {
      // refuse absurd sizes before GridGenerator tries them
      const double volume          = domain_volume(parameters);
      const double estimated_cells = volume / (h * h * h);
      if (!std::isfinite(volume) || !(volume > 0.) ||
          !std::isfinite(estimated_cells) || estimated_cells > 2e6)
        throw InputError(
          "Mesh: a domain of volume " + Utilities::to_string(volume) +
          " m^3 with Element size = " + Utilities::to_string(h) +
          " m would have about " + Utilities::to_string(estimated_cells) +
          " hexahedra; allowed are finite domains and at most 2e6 (then "
          "Mesh/Global refinements).");
    }

    const bool tetrahedra =
      parameters.element_type == MeshParameters::ElementType::triangles;
    Triangulation<3> hexahedra;
    if (parameters.source == Source::box)
      {
        const Tensor<1, 3> extent =
          parameters.upper_right - parameters.lower_left;
        std::vector<unsigned int> repetitions(3);
        for (unsigned int d = 0; d < 3; ++d)
          repetitions[d] = std::max(1u,
                                    static_cast<unsigned int>(
                                      std::ceil(extent[d] / h - 1e-9)));
        GridGenerator::subdivided_hyper_rectangle(hexahedra,
                                                  repetitions,
                                                  parameters.lower_left,
                                                  parameters.upper_right);
      }
    else
      {
        if (parameters.source == Source::ball)
          GridGenerator::hyper_ball(hexahedra,
                                    parameters.center,
                                    parameters.outer_radius);
        else
          GridGenerator::hyper_shell(hexahedra,
                                     parameters.center,
                                     parameters.inner_radius,
                                     parameters.outer_radius);
        refine_to_size_and_flatten(hexahedra, h);
      }
    set_boundary_ids(parameters, hexahedra);

    if (tetrahedra)
      {
        GridGenerator::convert_hypercube_to_simplex_mesh(hexahedra,
                                                         triangulation);
        set_boundary_ids(parameters, triangulation);
      }
    else
      {
        triangulation.copy_triangulation(hexahedra);
        if (parameters.source == Source::ball)
          {
            // the surface follows the sphere; inside, new vertices are
            // the mean of their parents (flat)
            for (const auto &cell : triangulation.active_cell_iterators())
              for (const auto &face : cell->face_iterators())
                if (face->at_boundary())
                  face->set_all_manifold_ids(sphere_manifold_id);
            triangulation.set_manifold(sphere_manifold_id,
                                       SphericalManifold<3>(parameters.center));
          }
        else if (parameters.source == Source::spherical_shell)
          {
            // every cell of the shell follows the spheres about the centre
            triangulation.set_all_manifold_ids(sphere_manifold_id);
            triangulation.set_manifold(sphere_manifold_id,
                                       SphericalManifold<3>(parameters.center));
          }
      }
    for (const auto &cell : triangulation.active_cell_iterators())
      cell->set_material_id(parameters.material_id);
  }
} // namespace tmfdem
