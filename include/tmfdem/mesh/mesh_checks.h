/**
 * @file
 * Checks that a mesh can be computed on: no inverted, degenerate or
 * duplicate cells, no unmeshed regions.
 */
#ifndef tmfdem_mesh_mesh_checks_h
#define tmfdem_mesh_mesh_checks_h

#include <deal.II/base/types.h>
#include <deal.II/grid/tria.h>

#include <set>
#include <string>

namespace tmfdem
{
  using namespace dealii;

  /** What a mesh holds, for `--validate` and summary.json. */
  struct MeshReport
  {
    unsigned int                 n_cells            = 0;
    unsigned int                 n_vertices         = 0;
    unsigned int                 n_triangles        = 0;
    unsigned int                 n_quadrilaterals   = 0;
    unsigned int                 n_tetrahedra       = 0; ///< 3D
    unsigned int                 n_hexahedra        = 0; ///< 3D
    unsigned int                 dimension          = 2; ///< [-]
    unsigned int                 n_connected_pieces = 0;
    double                       area = 0.; ///< [m^2]; in 3D the volume [m^3]
    double                       min_edge = 0., max_edge = 0.; ///< [m]
    double                       mean_edge = 0.;               ///< [m]
    std::set<types::boundary_id> boundary_ids;
    std::set<types::material_id> material_ids;

    /** One paragraph for the terminal. */
    std::string
    to_string() const;
  };

  /**
   * Checks the coarse @p triangulation and describes it. Throws InputError,
   * naming @p source (the file or generator) and the offending cell and its
   * vertices, for an inverted cell (negative Jacobian at a vertex), a
   * degenerate cell (area below 1e-10 of its squared longest edge), two cells
   * on the same vertices, or, when @p expected_area > 0, a mesh whose area
   * misses the domain's by more than the boundary approximation explains
   * (an unmeshed region): by 0.1 %, or with @p curved_boundary by what
   * polygonal approximation of circles explains.
   */
  MeshReport
  check_mesh(const Triangulation<2> &triangulation,
             const std::string      &source,
             const double            expected_area,
             const bool              curved_boundary);

  /**
   * The 3D checks of check_mesh() for tetrahedra and hexahedra: each cell
   * with a positive volume (the Jacobian at every vertex of a hexahedron),
   * no two cells on the same vertices, the volume against
   * @p expected_volume [m^3] (0: not checked; 2 % plus the curvature of
   * two longest edges where @p curved_boundary, 1e-3 otherwise).
   */
  MeshReport
  check_mesh(const Triangulation<3> &triangulation,
             const std::string      &source,
             const double            expected_volume,
             const bool              curved_boundary);
} // namespace tmfdem

#endif
