/**
 * @file
 * Meshes: generated rectangles, annuli and discs (unstructured triangles
 * through gmsh, or structured quadrilaterals through deal.II's GridGenerator),
 * and gmsh .msh import with physical groups mapped to ids.
 */
#ifndef tmfdem_mesh_mesh_generator_h
#define tmfdem_mesh_mesh_generator_h

#include <deal.II/distributed/tria_base.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <mpi.h>
#include <string>
#include <tmfdem/base/parameters.h>
#include <tmfdem/mesh/mesh_checks.h>

namespace tmfdem
{
  /**
   * Fills the serial @p triangulation as @p parameters describe (before
   * Mesh/Global refinements). Generated triangle meshes are written by the
   * `gmsh` program into @p work_folder (`mesh.geo`, `mesh.msh`, kept for the
   * user); rank 0 runs gmsh and every rank reads the result. Manifolds are
   * attached to curved boundaries. Throws InputError for missing or
   * unreadable files and RunError if gmsh fails.
   */
  void
  create_coarse_mesh(const MeshParameters &parameters,
                     const std::string    &work_folder,
                     Triangulation<2>     &triangulation,
                     MPI_Comm              communicator);

  /**
   * Reads a gmsh .msh file (ASCII format 2 or 4): physical curves become
   * boundary ids, physical surfaces material ids. Throws InputError naming
   * @p file_name if it is missing, unreadable or malformed.
   */
  void
  read_gmsh_file(const std::string &file_name, Triangulation<2> &triangulation);

  /** Exact area of a generated domain, or Mesh/Expected area for imported
   *  meshes (0: unknown) [m^2]. */
  double
  domain_area(const MeshParameters &parameters);

  /**
   * The continuum layer's triangulation: the coarse mesh of @p parameters
   * (generated or read, work files in @p work_folder), checked with
   * check_mesh (the result in @p report), distributed with p4est for
   * quadrilaterals or shared for triangles, and refined Mesh/Global
   * refinements times. Throws InputError for meshes that mix cell shapes.
   */
  std::unique_ptr<parallel::TriangulationBase<2>>
  create_continuum_triangulation(const MeshParameters &parameters,
                                 const std::string    &work_folder,
                                 MPI_Comm              communicator,
                                 MeshReport           &report);
} // namespace tmfdem

#endif
