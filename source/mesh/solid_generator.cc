/**
 * @file
 * The 3D coarse meshes of Mesh/Dimension = 3: a box, a ball, a spherical
 * shell, a cylinder and a hollow cylinder of hexahedra (or tetrahedra split
 * from them), and gmsh .msh files with tetrahedra or hexahedra.
 */
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <algorithm>
#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/mesh/block_generator.h>
#include <tmfdem/mesh/mesh_generator.h>

namespace tmfdem
{
  namespace
  {
    /** Manifold id of the cells and faces that follow a sphere (or the
     *  cylinders about the axis of a cylinder). */
    constexpr types::manifold_id sphere_manifold_id = 1;

    bool
    is_cylinder(const MeshParameters &parameters)
    {
      return parameters.source == MeshParameters::Source::cylinder ||
             parameters.source == MeshParameters::Source::hollow_cylinder;
    }

    /**
     * The cylinder or hollow cylinder of @p parameters as hexahedra: the 2D
     * disc or annulus of the same radii and Element size (mesh_generator.cc)
     * extruded along z in layers no thicker than the Element size, centred
     * at Center.
     */
    void
    create_cylinder(const MeshParameters &parameters,
                    const std::string    &work_folder,
                    Triangulation<3>     &hexahedra,
                    MPI_Comm              communicator)
    {
      MeshParameters section = parameters;
      section.dimension      = 2;
      section.element_type   = MeshParameters::ElementType::quadrilaterals;
      section.source = parameters.source == MeshParameters::Source::cylinder ?
                         MeshParameters::Source::disc :
                         MeshParameters::Source::annulus;
      Triangulation<2> disc;
      create_coarse_mesh(section, work_folder, disc, communicator);
      const double       h = parameters.element_size, L = parameters.length;
      const unsigned int n_layers =
        std::max(1u, static_cast<unsigned int>(std::ceil(L / h - 1e-9)));
      GridGenerator::extrude_triangulation(disc, n_layers + 1, L, hexahedra);
      Tensor<1, 3> shift;
      shift[2] = parameters.center[2] - 0.5 * L;
      GridTools::shift(shift, hexahedra);
    }

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
              else if (is_cylinder(parameters))
                {
                  // ends by z; mantles by the distance from the axis
                  const double z_bottom =
                    parameters.center[2] - 0.5 * parameters.length;
                  const double tolerance = 1e-6 * parameters.length;
                  const double r = std::hypot(c[0] - parameters.center[0],
                                              c[1] - parameters.center[1]);
                  if (std::abs(c[2] - z_bottom) < tolerance)
                    face->set_boundary_id(2);
                  else if (std::abs(c[2] - z_bottom - parameters.length) <
                           tolerance)
                    face->set_boundary_id(3);
                  else if (parameters.source == Source::hollow_cylinder &&
                           r < 0.5 * (parameters.inner_radius +
                                      parameters.outer_radius))
                    face->set_boundary_id(0);
                  else
                    face->set_boundary_id(1);
                }
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
        case Source::cylinder:
          return numbers::PI * p.outer_radius * p.outer_radius * p.length;
        case Source::hollow_cylinder:
          return numbers::PI *
                 (p.outer_radius * p.outer_radius -
                  p.inner_radius * p.inner_radius) *
                 p.length;
        case Source::block_heap:
          return generate_block_heap_3d(p).volume();
        default:
          return p.expected_area;
      }
  }

  void
  create_coarse_mesh(const MeshParameters &parameters,
                     const std::string    &work_folder,
                     Triangulation<3>     &triangulation,
                     MPI_Comm              communicator)
  {
    using Source = MeshParameters::Source;
    if (parameters.source == Source::file)
      {
        read_mesh_file(parameters, work_folder, triangulation, communicator);
        return;
      }
    if (parameters.source == Source::block_heap)
      {
        create_block_heap_mesh(parameters,
                               work_folder,
                               triangulation,
                               communicator);
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
    else if (is_cylinder(parameters))
      create_cylinder(parameters, work_folder, hexahedra, communicator);
    else
      {
        if (parameters.source == Source::ball)
          GridGenerator::hyper_ball(hexahedra,
                                    parameters.center,
                                    parameters.outer_radius);
        else
          {
            // hexahedra: deal.II's six cells (one per face of a cube);
            // tetrahedra: six or 24 cells (each cube face split in four),
            // whichever makes the cells' arc at the mean radius closer to
            // the wall thickness, since the joints of flat tetrahedra take
            // much of their compliance (theory 5.12)
            const double a      = parameters.inner_radius,
                         b      = parameters.outer_radius;
            const double arc_6  = 0.5 * numbers::PI * 0.5 * (a + b);
            const auto   aspect = [&](const double arc) {
              return std::abs(std::log(arc / (b - a)));
            };
            const unsigned int n_cells =
              tetrahedra && aspect(0.5 * arc_6) < aspect(arc_6) ? 24 : 6;
            GridGenerator::hyper_shell(hexahedra,
                                       parameters.center,
                                       a,
                                       b,
                                       n_cells);
          }
        refine_to_size_and_flatten(hexahedra, h);
        if (parameters.source == Source::spherical_shell &&
            parameters.radial_grading != 1.)
          {
            // the uniform layers moved to r = a + (b - a) xi^p along their
            // rays from the centre
            const double a = parameters.inner_radius,
                         b = parameters.outer_radius,
                         p = parameters.radial_grading;
            GridTools::transform(
              [&](const Point<3> &x) {
                const Tensor<1, 3> ray = x - parameters.center;
                const double       r   = ray.norm();
                const double       xi  = std::clamp((r - a) / (b - a), 0., 1.);
                return Point<3>(parameters.center +
                                (a + (b - a) * std::pow(xi, p)) / r * ray);
              },
              hexahedra);
          }
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
        else if (parameters.source == Source::hollow_cylinder)
          {
            // every cell follows the cylinders about the axis (as the 2D
            // annulus follows its circles)
            triangulation.set_all_manifold_ids(sphere_manifold_id);
            triangulation.set_manifold(
              sphere_manifold_id,
              CylindricalManifold<3>(Tensor<1, 3>({0., 0., 1.}),
                                     parameters.center));
          }
        else if (parameters.source == Source::cylinder)
          {
            // the mantle follows the cylinder (as the 2D disc's rim)
            for (const auto &cell : triangulation.active_cell_iterators())
              for (const auto &face : cell->face_iterators())
                if (face->at_boundary() && face->boundary_id() == 1)
                  face->set_all_manifold_ids(sphere_manifold_id);
            triangulation.set_manifold(
              sphere_manifold_id,
              CylindricalManifold<3>(Tensor<1, 3>({0., 0., 1.}),
                                     parameters.center));
          }
      }
    for (const auto &cell : triangulation.active_cell_iterators())
      cell->set_material_id(parameters.material_id);
  }
} // namespace tmfdem
