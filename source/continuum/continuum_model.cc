#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/sparsity_tools.h>

#include <tmfdem/base/exceptions.h>
#include <tmfdem/continuum/adaptivity.h>
#include <tmfdem/continuum/continuum_model.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/monitors.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/mesh/mesh_checks.h>
#include <tmfdem/mesh/mesh_generator.h>

namespace tmfdem
{
  template <int dim>
  ContinuumModel<dim>::ContinuumModel(const Parameters &parameters,
                                      MPI_Comm          communicator)
    : parameters(parameters)
    , communicator(communicator)
  {}

  template <int dim>
  ContinuumModel<dim>::~ContinuumModel()
  {
    if (dof_handler)
      dof_handler->clear();
  }

  template <int dim>
  const DoFHandler<dim> &
  ContinuumModel<dim>::get_dof_handler() const
  {
    return *dof_handler;
  }

  template <int dim>
  const Mapping<dim> &
  ContinuumModel<dim>::get_mapping() const
  {
    return *mapping;
  }

  template <int dim>
  parallel::TriangulationBase<dim> &
  ContinuumModel<dim>::get_triangulation()
  {
    return *triangulation;
  }

  template <int dim>
  void
  ContinuumModel<dim>::refuse_resume() const
  {
    if (parameters.resume)
      throw InputError(
        "--resume: the continuum models do not write checkpoints; run the "
        "case again without --resume (SIGINT/SIGTERM stop them cleanly with "
        "the outputs so far). Checkpoints are for the discrete models.");
  }

  // ------------------------------------------------------------ mesh
  template <int dim>
  void
  ContinuumModel<dim>::create_mesh()
  {
    create_output_folder(parameters.output.directory, communicator);
    mesh_report = std::make_unique<MeshReport>();
    own_triangulation =
      create_continuum_triangulation<dim>(parameters.mesh,
                                          parameters.output.directory,
                                          communicator,
                                          *mesh_report);
    triangulation = own_triangulation.get();
    describe_mesh();
  }

  template <int dim>
  void
  ContinuumModel<dim>::use_mesh(parallel::TriangulationBase<dim> &external)
  {
    triangulation = &external;
    describe_mesh();
  }

  template <int dim>
  void
  ContinuumModel<dim>::describe_mesh()
  {
    coarse_level = parameters.mesh.global_refinements;
    mesh_boundary_ids.clear();
    mesh_material_ids.clear();
    for (const auto &cell : triangulation->cell_iterators_on_level(0))
      {
        mesh_material_ids.insert(cell->material_id());
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            mesh_boundary_ids.insert(face->boundary_id());
      }
    // Mesh/... never mixes cell shapes (create_continuum_triangulation)
    quadrilaterals = triangulation->begin()->reference_cell() ==
                     ReferenceCells::get_hypercube<dim>();
  }

  template <int dim>
  void
  ContinuumModel<dim>::create_fe(const unsigned int degree,
                                 const unsigned int n_components)
  {
    std::unique_ptr<FiniteElement<dim>> scalar;
    if (uses_quadrilaterals())
      {
        scalar  = std::make_unique<FE_Q<dim>>(degree);
        mapping = std::make_unique<MappingQ<dim>>(degree);
      }
    else
      {
        // deal.II 9.4 has triangle elements of degrees 1 and 2 only (its
        // FE_SimplexP(3) crashes in a release build)
        if (degree > 2)
          throw InputError(
            std::string(n_components == 1 ? "Heat solver" : "Mechanics") +
            "/Polynomial degree = " + std::to_string(degree) +
            ": the mesh is made of triangles, whose elements (deal.II 9.4) "
            "have degree 1 or 2; allowed are 1 and 2 on triangles, 1 to 3 "
            "on quadrilaterals (Mesh/Element type, or a quadrilateral mesh "
            "file).");
        scalar  = std::make_unique<FE_SimplexP<dim>>(degree);
        mapping = std::make_unique<MappingFE<dim>>(FE_SimplexP<dim>(1));
      }
    if (n_components == 1)
      fe = std::move(scalar);
    else
      fe = std::make_unique<FESystem<dim>>(*scalar, n_components);
    dof_handler = std::make_unique<DoFHandler<dim>>(*triangulation);
  }

  // ------------------------------------------------------------ checks
  template <int dim>
  void
  ContinuumModel<dim>::check_boundary_ids(
    const std::string                     &name,
    const std::vector<types::boundary_id> &ids) const
  {
    for (const auto id : ids)
      if (mesh_boundary_ids.count(id) == 0)
        {
          std::string mesh_ids;
          for (const auto known : mesh_boundary_ids)
            mesh_ids += " " + std::to_string(known);
          throw InputError(
            name + "/Boundary ids: boundary id " + std::to_string(id) +
            " is not on the mesh; the mesh has boundary ids" + mesh_ids + ".");
        }
  }

  template <int dim>
  void
  ContinuumModel<dim>::check_material_ids() const
  {
    // ids without a subsection (or beyond them) are refused
    for (const auto id : mesh_material_ids)
      parameters.materials.require_given(
        id,
        "cells of the " +
          std::string(parameters.mesh.source == MeshParameters::Source::file ?
                        "mesh file '" + parameters.mesh.file_name + "'" :
                        "generated mesh (Mesh/Material id)"));
  }

  template <int dim>
  void
  ContinuumModel<dim>::check_adaptivity() const
  {
    if (parameters.adaptivity.enable && !uses_quadrilaterals())
      throw InputError(
        "Adaptive refinement/Enable = true needs a quadrilateral mesh: "
        "deal.II 9.4.1 cannot coarsen triangles and its Kelly estimator fails "
        "on triangle meshes with hanging nodes. Set Mesh/Element type = "
        "quadrilaterals, or use Mesh/Global refinements on triangles.");
  }

  // ------------------------------------------------------------ DoFs
  template <int dim>
  void
  ContinuumModel<dim>::distribute_dofs()
  {
    dof_handler->distribute_dofs(*fe);
    locally_owned_dofs = dof_handler->locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(*dof_handler,
                                            locally_relevant_dofs);
  }

  template <int dim>
  DynamicSparsityPattern
  ContinuumModel<dim>::distributed_sparsity(
    const AffineConstraints<double> *constraints) const
  {
    DynamicSparsityPattern sparsity(locally_relevant_dofs);
    if (constraints)
      DoFTools::make_sparsity_pattern(*dof_handler,
                                      sparsity,
                                      *constraints,
                                      false);
    else
      DoFTools::make_sparsity_pattern(*dof_handler, sparsity);
    SparsityTools::distribute_sparsity_pattern(sparsity,
                                               locally_owned_dofs,
                                               communicator,
                                               locally_relevant_dofs);
    return sparsity;
  }

  template <int dim>
  Quadrature<dim>
  ContinuumModel<dim>::cell_quadrature() const
  {
    return uses_quadrilaterals() ?
             Quadrature<dim>(QGauss<dim>(fe->degree + 1)) :
             Quadrature<dim>(QGaussSimplex<dim>(fe->degree + 1));
  }

  template <int dim>
  Quadrature<dim - 1>
  ContinuumModel<dim>::face_quadrature_rule() const
  {
    if (dim == 2 || uses_quadrilaterals())
      return QGauss<dim - 1>(fe->degree + 1);
    return QGaussSimplex<dim - 1>(fe->degree + 1);
  }

  // ------------------------------------------------------------ output
  template <int dim>
  OutputSchedule
  ContinuumModel<dim>::output_schedule() const
  {
    return OutputSchedule(parameters.output,
                          parameters.time.start_time,
                          parameters.time.end_time);
  }

  template <int dim>
  JsonObject
  ContinuumModel<dim>::summary_head() const
  {
    JsonObject summary;
    summary.add("model", parameters.model)
      .add("prm_file", parameters.prm_file)
      .add("mpi_processes", Utilities::MPI::n_mpi_processes(communicator));
    return summary;
  }

  template <int dim>
  void
  ContinuumModel<dim>::add_run_entries(JsonObject         &summary,
                                       const unsigned long steps,
                                       const double        end_time,
                                       const double        wall_time) const
  {
    summary
      .add("cells",
           static_cast<long long>(triangulation->n_global_active_cells()))
      .add("dofs", static_cast<long long>(dof_handler->n_dofs()))
      .add("steps", static_cast<long long>(steps))
      .add("end_time", end_time)
      .add("wall_time", wall_time)
      .add("element_steps_per_second",
           wall_time > 0 ?
             triangulation->n_global_active_cells() *
               static_cast<double>(std::max(steps, 1ul)) / wall_time :
             0.);
  }

  template <int dim>
  void
  ContinuumModel<dim>::open_solution_series()
  {
    solution_series =
      std::make_unique<SolutionSeries>(parameters.output.directory,
                                       "solution",
                                       communicator,
                                       parameters.output.binary_vtu);
  }

  template <int dim>
  void
  ContinuumModel<dim>::write_solution(DataOut<dim> &data_out, const double time)
  {
    Vector<float> material(triangulation->n_active_cells()),
      subdomain(triangulation->n_active_cells());
    for (const auto &cell : triangulation->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          material(cell->active_cell_index())  = cell->material_id();
          subdomain(cell->active_cell_index()) = cell->subdomain_id();
        }
    data_out.add_data_vector(material, "material_id");
    data_out.add_data_vector(subdomain, "subdomain");
    data_out.build_patches(*mapping, uses_quadrilaterals() ? fe->degree : 1);
    solution_series->write(data_out, time);
  }

  // ------------------------------------------------------------ AMR
  template <int dim>
  void
  ContinuumModel<dim>::refine_mesh_by_kelly(
    const TrilinosWrappers::MPI::Vector &solution,
    const std::function<void()>         &after_refinement,
    TrilinosWrappers::MPI::Vector       *transferred)
  {
    auto &distributed_triangulation =
      dynamic_cast<parallel::distributed::Triangulation<dim> &>(*triangulation);
    mark_cells_by_kelly(distributed_triangulation,
                        *mapping,
                        *dof_handler,
                        solution,
                        fe->degree,
                        parameters.adaptivity,
                        coarse_level);
    parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector>
      transfer(*dof_handler);
    triangulation->prepare_coarsening_and_refinement();
    if (transferred)
      transfer.prepare_for_coarsening_and_refinement(solution);
    triangulation->execute_coarsening_and_refinement();
    after_refinement();
    if (transferred)
      {
        transferred->reinit(locally_owned_dofs, communicator);
        transfer.interpolate(*transferred);
      }
  }

  // ------------------------------------------------------------ stop
  template <int dim>
  void
  ContinuumModel<dim>::stop_if_requested(
    const double                 time,
    const unsigned long          step,
    const std::function<void()> &write_state) const
  {
    if (!stop_requested_on_any_rank(communicator))
      return;
    write_state();
    throw StopRequested("stopped by " + stop_signal_name() +
                        " at t = " + Utilities::to_string(time) +
                        " s after step " + std::to_string(step) +
                        "; outputs so far in " + parameters.output.directory +
                        " (continuum runs cannot be resumed).");
  }
  template class ContinuumModel<2>;
  template class ContinuumModel<3>;
} // namespace tmfdem
