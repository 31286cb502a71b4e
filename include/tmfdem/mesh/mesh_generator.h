/**
 * @file
 * Meshes: generated rectangles, annuli and discs (unstructured triangles
 * through gmsh, or structured quadrilaterals through deal.II's GridGenerator),
 * generated boxes, balls and spherical shells in 3D (hexahedra, or
 * tetrahedra split from them; source/mesh/solid_generator.cc), and gmsh .msh
 * import with physical groups mapped to ids.
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
   * The 3D coarse mesh of @p parameters (Mesh/Dimension = 3): a box, ball
   * or spherical shell of hexahedra of edge about Mesh/Element size (the
   * coarse cells of deal.II's GridGenerator refined and flattened), split
   * into tetrahedra for Element type = triangles
   * (GridGenerator::convert_hypercube_to_simplex_mesh, 24 per hexahedron),
   * or a gmsh .msh file. Boundary ids as Mesh/Source documents; hexahedra
   * of the ball and shell follow the sphere on refinement (a spherical
   * manifold), tetrahedra keep their flat faces.
   */
  void
  create_coarse_mesh(const MeshParameters &parameters,
                     const std::string    &work_folder,
                     Triangulation<3>     &triangulation,
                     MPI_Comm              communicator);

  /**
   * Reads Mesh/File name of @p parameters into @p triangulation: a gmsh
   * .msh file (read_gmsh_file()), or a .geo script that gmsh meshes in
   * @p dim dimensions (gmsh -2 or -3, format 2.2) into
   * <@p work_folder>/mesh.msh first, stopped after Mesh/Gmsh time limit.
   * gmsh's errors in the script and a mesh that takes longer than the limit
   * are InputError with gmsh's own error lines; a missing file is
   * InputError naming Mesh/File name.
   */
  template <int dim>
  void
  read_mesh_file(const MeshParameters &parameters,
                 const std::string    &work_folder,
                 Triangulation<dim>   &triangulation,
                 MPI_Comm              communicator);

  /**
   * Reads a gmsh .msh file (ASCII format 2 or 4): in 2D physical curves
   * become boundary ids, physical surfaces material ids; in 3D physical
   * surfaces become boundary ids, physical volumes material ids. Throws
   * InputError naming
   * @p file_name if it is missing, unreadable or malformed.
   */
  template <int dim>
  void
  read_gmsh_file(const std::string  &file_name,
                 Triangulation<dim> &triangulation);

  /** Exact area of a generated domain, or Mesh/Expected area for imported
   *  meshes (0: unknown) [m^2]. */
  /**
   * Source = block heap in 3D (mesh/block_generator.h): the heap's .geo
   * script written to @p work_folder and meshed there by gmsh into
   * tetrahedra.
   */
  void
  create_block_heap_mesh(const MeshParameters &parameters,
                         const std::string    &work_folder,
                         Triangulation<3>     &triangulation,
                         MPI_Comm              communicator);

  double
  domain_area(const MeshParameters &parameters);

  /** Exact volume of a generated 3D domain, or Mesh/Expected area (the
   *  volume in 3D) for imported meshes (0: unknown) [m^3]. */
  double
  domain_volume(const MeshParameters &parameters);

  /**
   * The continuum layer's triangulation: the coarse mesh of @p parameters
   * (generated or read, work files in @p work_folder), checked with
   * check_mesh (the result in @p report), distributed with p4est for
   * quadrilaterals and hexahedra or shared for triangles and tetrahedra,
   * and refined Mesh/Global refinements times. Throws InputError for meshes
   * that mix cell shapes.
   */
  template <int dim>
  std::unique_ptr<parallel::TriangulationBase<dim>>
  create_continuum_triangulation(const MeshParameters &parameters,
                                 const std::string    &work_folder,
                                 MPI_Comm              communicator,
                                 MeshReport           &report);
} // namespace tmfdem

#endif
