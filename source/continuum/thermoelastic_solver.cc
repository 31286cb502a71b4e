#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_local_storage.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/continuum/adaptivity.h>
#include <tmfdem/continuum/heat_solver.h>
#include <tmfdem/continuum/thermoelastic_solver.h>
#include <tmfdem/coupling/discrete_heat_field.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/monitors.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/mesh/mesh_generator.h>

namespace tmfdem
{
  namespace
  {
    const bool registered = register_simulation(
      "continuum thermoelastic",
      "quasi-static thermal stress with deal.II: small or finite strain, "
      "plane stress or plane strain, temperature from a function or the "
      "continuum heat solver (Newton, AMR on quadrilaterals, MPI)",
      [](const Parameters &parameters, MPI_Comm communicator) {
        return std::make_unique<ThermoelasticSolver>(parameters, communicator);
      });

    using Condition = MechanicalBoundaryCondition;

    double
    wall_clock()
    {
      return std::chrono::duration<double>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
    }

    /** Two parsed expressions as one vector-valued function. */
    class VectorExpression : public Function<2>
    {
    public:
      VectorExpression(
        const std::array<std::unique_ptr<FunctionParser<2>>, 2> &components,
        const double                                             time)
        : Function<2>(2, time)
        , components(components)
      {}
      double
      value(const Point<2> &p, const unsigned int component) const override
      {
        components[component]->set_time(this->get_time());
        return components[component]->value(p);
      }

    private:
      const std::array<std::unique_ptr<FunctionParser<2>>, 2> &components;
    };

    /** The reference-cell coordinates of @p p in @p cell. */
    Point<2>
    unit_point_of(const Mapping<2>                             &mapping,
                  const Triangulation<2>::active_cell_iterator &cell,
                  const Point<2>                               &p)
    {
      if (cell->reference_cell() == ReferenceCells::Triangle)
        {
          const Tensor<1, 2> a = cell->vertex(1) - cell->vertex(0),
                             b = cell->vertex(2) - cell->vertex(0),
                             d = p - cell->vertex(0);
          const double det     = a[0] * b[1] - a[1] * b[0];
          return Point<2>((d[0] * b[1] - d[1] * b[0]) / det,
                          (a[0] * d[1] - a[1] * d[0]) / det);
        }
      return mapping.transform_real_to_unit_cell(cell, p);
    }
  } // namespace

  /**
   * Stress (Cauchy, tension positive), strain and temperature for the vtu
   * files, computed from the displacement gradient at each output point.
   */
  class ThermoelasticPostprocessor : public DataPostprocessor<2>
  {
  public:
    ThermoelasticPostprocessor(
      const std::vector<ThermoelasticMaterial> &materials,
      const Mapping<2>                         &mapping,
      const std::function<
        std::vector<double>(const Triangulation<2>::active_cell_iterator &,
                            const std::vector<Point<2>> &,
                            const std::vector<Point<2>> &)> &temperatures,
      const bool                                             with_szz)
      : materials(materials)
      , mapping(mapping)
      , temperatures(temperatures)
      , with_szz(with_szz)
    {}

    std::vector<std::string>
    get_names() const override
    {
      std::vector<std::string> names = {"sxx", "syy", "sxy"};
      if (with_szz)
        names.push_back("szz");
      for (const char *name : {"exx", "eyy", "exy", "T"})
        names.push_back(name);
      return names;
    }

    UpdateFlags
    get_needed_update_flags() const override
    {
      return update_gradients | update_quadrature_points;
    }

    void
    evaluate_vector_field(const DataPostprocessorInputs::Vector<2> &inputs,
                          std::vector<Vector<double>> &computed) const override
    {
      const auto dof_cell = inputs.template get_cell<2>();
      const Triangulation<2>::active_cell_iterator cell(
        &dof_cell->get_triangulation(),
        dof_cell->level(),
        dof_cell->index());
      const auto           &points = inputs.evaluation_points;
      std::vector<Point<2>> unit_points;
      for (const auto &p : points)
        unit_points.push_back(unit_point_of(mapping, cell, p));
      const std::vector<double> T = temperatures(cell, unit_points, points);
      const auto               &material = materials[cell->material_id()];
      for (unsigned int q = 0; q < points.size(); ++q)
        {
          Tensor<2, 2> grad_u;
          for (unsigned int c = 0; c < 2; ++c)
            grad_u[c] = inputs.solution_gradients[q][c];
          const Tensor<2, 2> sigma  = material.cauchy(grad_u, T[q]);
          const Tensor<2, 2> strain = material.strain(grad_u);
          unsigned int       k      = 0;
          computed[q](k++)          = sigma[0][0];
          computed[q](k++)          = sigma[1][1];
          computed[q](k++)          = sigma[0][1];
          if (with_szz)
            computed[q](k++) = material.out_of_plane_stress(sigma, T[q]);
          computed[q](k++) = strain[0][0];
          computed[q](k++) = strain[1][1];
          computed[q](k++) = strain[0][1];
          computed[q](k++) = T[q];
        }
    }

  private:
    const std::vector<ThermoelasticMaterial> &materials;
    const Mapping<2>                         &mapping;
    const std::function<
      std::vector<double>(const Triangulation<2>::active_cell_iterator &,
                          const std::vector<Point<2>> &,
                          const std::vector<Point<2>> &)>
               temperatures;
    const bool with_szz;
  };

  // ------------------------------------------------------------ set up
  ThermoelasticSolver::ThermoelasticSolver(const Parameters &parameters,
                                           MPI_Comm          communicator)
    : parameters(parameters)
    , communicator(communicator)
  {
    for (const auto &properties : parameters.materials.materials)
      materials.emplace_back(properties, parameters.mechanics);
    temperature_function =
      make_expression_function(parameters.mechanics.temperature,
                               "Mechanics/Temperature");
    temperature_field = [this](const Triangulation<2>::active_cell_iterator &,
                               const std::vector<Point<2>> &,
                               const std::vector<Point<2>> &points,
                               std::vector<double>         &temperatures) {
      for (unsigned int q = 0; q < points.size(); ++q)
        temperatures[q] = temperature_function->value(points[q]);
    };
    const char *axes[] = {"x", "y"};
    for (const auto &condition : parameters.mechanical_boundary.conditions)
      {
        std::array<std::unique_ptr<FunctionParser<2>>, 2> displacement,
          traction;
        for (unsigned int d = 0; d < 2; ++d)
          {
            displacement[d] =
              make_expression_function(condition.displacement[d],
                                       condition.name + "/Displacement " +
                                         axes[d]);
            traction[d] =
              make_expression_function(condition.traction[d],
                                       condition.name + "/Traction " + axes[d]);
          }
        displacement_functions.push_back(std::move(displacement));
        traction_functions.push_back(std::move(traction));
      }
    wall_start = wall_clock();
  }

  ThermoelasticSolver::~ThermoelasticSolver()
  {
    mesh_change_connection.disconnect();
    if (dof_handler)
      dof_handler->clear();
  }

  bool
  ThermoelasticSolver::uses_quadrilaterals() const
  {
    return triangulation->begin_active()->reference_cell() ==
           ReferenceCells::Quadrilateral;
  }

  const DoFHandler<2> &
  ThermoelasticSolver::get_dof_handler() const
  {
    return *dof_handler;
  }

  const TrilinosWrappers::MPI::Vector &
  ThermoelasticSolver::get_displacement() const
  {
    return solution;
  }

  parallel::TriangulationBase<2> &
  ThermoelasticSolver::get_triangulation()
  {
    return *triangulation;
  }

  void
  ThermoelasticSolver::set_temperature(const TemperatureField &field)
  {
    temperature_field = field;
  }

  void
  ThermoelasticSolver::set_temperature(
    const DoFHandler<2>                 &temperature_dofs,
    const Mapping<2>                    &temperature_mapping,
    const TrilinosWrappers::MPI::Vector &temperature)
  {
    // FEValues cached for the last set of unit points (the quadrature
    // points during assembly), rebuilt when they change; one cache per
    // thread: assembly and DataOut's postprocessor call this from TBB tasks
    struct Cache
    {
      std::vector<Point<2>>        unit_points;
      std::unique_ptr<FEValues<2>> fe_values;
    };
    auto caches = std::make_shared<Threads::ThreadLocalStorage<Cache>>();
    temperature_field =
      [&temperature_dofs,
       &temperature_mapping,
       &temperature,
       caches](const Triangulation<2>::active_cell_iterator &cell,
               const std::vector<Point<2>>                  &unit_points,
               const std::vector<Point<2>> &,
               std::vector<double> &temperatures) {
        Cache &cache = caches->get();
        if (!cache.fe_values || cache.unit_points != unit_points)
          {
            cache.unit_points = unit_points;
            cache.fe_values =
              std::make_unique<FEValues<2>>(temperature_mapping,
                                            temperature_dofs.get_fe(),
                                            Quadrature<2>(unit_points),
                                            update_values);
          }
        const DoFHandler<2>::active_cell_iterator temperature_cell(
          &cell->get_triangulation(),
          cell->level(),
          cell->index(),
          &temperature_dofs);
        cache.fe_values->reinit(temperature_cell);
        cache.fe_values->get_function_values(temperature, temperatures);
      };
  }

  std::vector<double>
  ThermoelasticSolver::temperatures_at(
    const Triangulation<2>::active_cell_iterator &cell,
    const std::vector<Point<2>>                  &unit_points,
    const std::vector<Point<2>>                  &points) const
  {
    std::vector<double> temperatures(points.size());
    temperature_field(cell, unit_points, points, temperatures);
    return temperatures;
  }

  void
  ThermoelasticSolver::check_boundary_conditions() const
  {
    std::string mesh_ids;
    for (const auto id : mesh_boundary_ids)
      mesh_ids += " " + std::to_string(id);
    for (const auto &condition : parameters.mechanical_boundary.conditions)
      {
        if (condition.type == Condition::Type::velocity)
          throw InputError(
            condition.name +
            "/Type = velocity: prescribed velocities are for the discrete "
            "layer only; the continuum thermoelastic solver is quasi-static "
            "and accepts fixed, roller x, roller y, displacement and "
            "traction.");
        for (const auto id : condition.boundary_ids)
          if (mesh_boundary_ids.count(id) == 0)
            throw InputError(condition.name + "/Boundary ids: boundary id " +
                             std::to_string(id) +
                             " is not on the mesh; the mesh has boundary ids" +
                             mesh_ids + ".");
      }
    for (const auto &cell : triangulation->active_cell_iterators())
      if (cell->is_locally_owned())
        parameters.materials[cell->material_id()]; // throws for bad ids
    if (parameters.adaptivity.enable && !uses_quadrilaterals())
      throw InputError(
        "Adaptive refinement/Enable = true needs a quadrilateral mesh: "
        "deal.II 9.4.1 cannot coarsen triangles and its Kelly estimator fails "
        "on triangle meshes with hanging nodes. Set Mesh/Element type = "
        "quadrilaterals, or use Mesh/Global refinements on triangles.");
  }

  void
  ThermoelasticSolver::setup(parallel::TriangulationBase<2> *external)
  {
    if (external != nullptr)
      triangulation = external;
    else
      {
        create_output_folder(parameters.output.directory, communicator);
        MeshReport report;
        own_triangulation =
          create_continuum_triangulation(parameters.mesh,
                                         parameters.output.directory,
                                         communicator,
                                         report);
        triangulation = own_triangulation.get();
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          std::cout << report.to_string();
      }
    coarse_level = parameters.mesh.global_refinements;
    mesh_change_connection.disconnect();
    mesh_change_connection = triangulation->signals.any_change.connect(
      [this]() { mesh_changed = true; });
    // the coarse mesh is known to every rank
    mesh_boundary_ids.clear();
    for (const auto &cell : triangulation->cell_iterators_on_level(0))
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          mesh_boundary_ids.insert(face->boundary_id());

    const unsigned int degree = parameters.mechanics.degree;
    if (uses_quadrilaterals())
      {
        fe      = std::make_unique<FESystem<2>>(FE_Q<2>(degree), 2);
        mapping = std::make_unique<MappingQ<2>>(degree);
      }
    else
      {
        fe      = std::make_unique<FESystem<2>>(FE_SimplexP<2>(degree), 2);
        mapping = std::make_unique<MappingFE<2>>(FE_SimplexP<2>(1));
      }
    check_boundary_conditions();
    dof_handler = std::make_unique<DoFHandler<2>>(*triangulation);
    setup_dofs();
    domain_area = GridTools::volume(*triangulation, *mapping);

    std::vector<std::string> fields = {"T", "ux", "uy", "sxx", "syy", "sxy"};
    if (parameters.mechanics.polar_frame)
      {
        fields.push_back("srr");
        fields.push_back("stt");
      }
    monitors = std::make_unique<Monitors>(parameters.monitors,
                                          parameters.output.directory,
                                          fields,
                                          communicator);
    monitors->check_points(*mapping, *dof_handler);
    solution_series =
      std::make_unique<SolutionSeries>(parameters.output.directory,
                                       "solution",
                                       communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cout << "thermoelastic: " << triangulation->n_global_active_cells()
                << " cells, " << dof_handler->n_dofs()
                << " displacement dofs (degree " << degree << ")" << std::endl;
  }

  void
  ThermoelasticSolver::setup_dofs()
  {
    dof_handler->distribute_dofs(*fe);
    locally_owned_dofs = dof_handler->locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(*dof_handler,
                                            locally_relevant_dofs);
    hanging_node_constraints.clear();
    hanging_node_constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(*dof_handler,
                                            hanging_node_constraints);
    hanging_node_constraints.close();
    find_pinned_dofs();

    // the sparsity pattern with every DoF that may be constrained kept free
    DynamicSparsityPattern pattern(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(*dof_handler,
                                    pattern,
                                    hanging_node_constraints,
                                    false);
    SparsityTools::distribute_sparsity_pattern(pattern,
                                               locally_owned_dofs,
                                               communicator,
                                               locally_relevant_dofs);
    system_matrix.reinit(locally_owned_dofs,
                         locally_owned_dofs,
                         pattern,
                         communicator);
    system_rhs.reinit(locally_owned_dofs, communicator);
    solution.reinit(locally_owned_dofs, locally_relevant_dofs, communicator);
    mesh_changed = false;
  }

  void
  ThermoelasticSolver::find_pinned_dofs()
  {
    pinned_dofs.clear();
    const unsigned int dofs_per_vertex = fe->n_dofs_per_vertex();
    std::vector<types::global_dof_index> cell_dofs(fe->n_dofs_per_cell());
    for (const auto &point : parameters.mechanics.pinned_points)
      {
        double found = 0.;
        for (const auto &cell : dof_handler->active_cell_iterators())
          if (!cell->is_artificial())
            for (const auto v : cell->vertex_indices())
              if (cell->vertex(v).distance(point.location) <
                  1e-6 * cell->diameter())
                {
                  found = 1.;
                  cell->get_dof_indices(cell_dofs);
                  for (unsigned int i = 0; i < dofs_per_vertex; ++i)
                    {
                      const unsigned int local = v * dofs_per_vertex + i;
                      const unsigned int component =
                        fe->system_to_component_index(local).first;
                      if ((component == 0 && point.fix_x) ||
                          (component == 1 && point.fix_y))
                        pinned_dofs.push_back(cell_dofs[local]);
                    }
                }
        if (Utilities::MPI::max(found, communicator) == 0.)
          throw InputError("Mechanics/Pinned points: the point in '" +
                           point.text +
                           "' is not a vertex of the mesh; allowed are mesh "
                           "vertices (e.g. where a circle meets an axis).");
      }
    std::sort(pinned_dofs.begin(), pinned_dofs.end());
    pinned_dofs.erase(std::unique(pinned_dofs.begin(), pinned_dofs.end()),
                      pinned_dofs.end());
  }

  // ------------------------------------------------------------ assembly
  void
  ThermoelasticSolver::compute_quadrature_temperatures()
  {
    const Quadrature<2> quadrature =
      uses_quadrilaterals() ? Quadrature<2>(QGauss<2>(fe->degree + 1)) :
                              Quadrature<2>(QGaussSimplex<2>(fe->degree + 1));
    FEValues<2> fe_values(*mapping, *fe, quadrature, update_quadrature_points);
    quadrature_temperatures.assign(triangulation->n_active_cells(), {});
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          const Triangulation<2>::active_cell_iterator tria_cell(triangulation,
                                                                 cell->level(),
                                                                 cell->index());
          auto &T = quadrature_temperatures[cell->active_cell_index()];
          T       = temperatures_at(tria_cell,
                              quadrature.get_points(),
                              fe_values.get_quadrature_points());
          const auto &material = materials[cell->material_id()];
          for (const double value : T)
            if (!(material.thermal_stretch(value) > 0.) ||
                !std::isfinite(value))
              {
                std::ostringstream message;
                message << "thermoelastic solver: temperature " << value
                        << " C at a quadrature point of the cell at "
                        << cell->center()
                        << " gives a thermal stretch 1 + beta dT <= 0 (or is "
                           "not a number); check Mechanics/Temperature or "
                           "the heat solution.";
                throw RunError(message.str());
              }
        }
  }

  double
  ThermoelasticSolver::make_newton_constraints(const double time)
  {
    std::map<types::global_dof_index, double> prescribed;
    const Functions::ZeroFunction<2>          zero(2);
    const ComponentMask x_only(std::vector<bool>{true, false}),
      y_only(std::vector<bool>{false, true}), both(2, true);
    for (unsigned int n = 0;
         n < parameters.mechanical_boundary.conditions.size();
         ++n)
      {
        const auto &condition = parameters.mechanical_boundary.conditions[n];
        if (condition.type == Condition::Type::traction)
          continue;
        const VectorExpression displacement(displacement_functions[n], time);
        const Function<2>     &values =
          condition.type == Condition::Type::displacement ?
                static_cast<const Function<2> &>(displacement) :
                static_cast<const Function<2> &>(zero);
        const ComponentMask &mask =
          condition.type == Condition::Type::roller_x ? x_only :
          condition.type == Condition::Type::roller_y ? y_only :
                                                        both;
        for (const auto id : condition.boundary_ids)
          VectorTools::interpolate_boundary_values(*mapping,
                                                   *dof_handler,
                                                   id,
                                                   values,
                                                   prescribed,
                                                   mask);
      }
    for (const auto dof : pinned_dofs)
      prescribed[dof] = 0.;

    newton_constraints.clear();
    newton_constraints.reinit(locally_relevant_dofs);
    newton_constraints.merge(hanging_node_constraints);
    residual_constraints.clear();
    residual_constraints.reinit(locally_relevant_dofs);
    residual_constraints.merge(hanging_node_constraints);
    double largest_increment = 0.;
    for (const auto &[dof, value] : prescribed)
      if (locally_relevant_dofs.is_element(dof) &&
          !hanging_node_constraints.is_constrained(dof))
        {
          const double increment = value - solution(dof);
          newton_constraints.add_line(dof);
          newton_constraints.set_inhomogeneity(dof, increment);
          residual_constraints.add_line(dof);
          largest_increment = std::max(largest_increment, std::abs(increment));
        }
    newton_constraints.close();
    residual_constraints.close();
    return Utilities::MPI::max(largest_increment, communicator);
  }

  bool
  ThermoelasticSolver::assemble(
    const TrilinosWrappers::MPI::Vector &displacement,
    const AffineConstraints<double>     &constraints_used,
    const bool                           with_matrix)
  {
    const Quadrature<2> quadrature =
      uses_quadrilaterals() ? Quadrature<2>(QGauss<2>(fe->degree + 1)) :
                              Quadrature<2>(QGaussSimplex<2>(fe->degree + 1));
    const QGauss<1>                      face_quadrature(fe->degree + 1);
    FEValues<2>                          fe_values(*mapping,
                          *fe,
                          quadrature,
                          update_gradients | update_JxW_values);
    FEFaceValues<2>                      fe_face_values(*mapping,
                                   *fe,
                                   face_quadrature,
                                   update_values | update_quadrature_points |
                                     update_JxW_values);
    const unsigned int                   n_dofs = fe->n_dofs_per_cell();
    const unsigned int                   n_q    = quadrature.size();
    const FEValuesExtractors::Vector     u(0);
    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs);
    Vector<double>                       cell_rhs(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    std::vector<Tensor<2, 2>>            grad_u(n_q);
    std::vector<Tensor<2, 2>>            shape_gradients(n_dofs);
    std::vector<Tensor<2, 2>>            tangent_times_gradient(n_dofs);

    std::vector<int> traction_condition(256, -1);
    for (unsigned int n = 0;
         n < parameters.mechanical_boundary.conditions.size();
         ++n)
      {
        const auto &condition = parameters.mechanical_boundary.conditions[n];
        if (condition.type == Condition::Type::traction)
          for (const auto id : condition.boundary_ids)
            if (id < traction_condition.size())
              traction_condition[id] = n;
      }

    if (with_matrix)
      system_matrix = 0;
    system_rhs        = 0;
    double admissible = 1.;
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          cell_rhs    = 0;
          fe_values[u].get_function_gradients(displacement, grad_u);
          const auto &material = materials[cell->material_id()];
          const auto &T = quadrature_temperatures[cell->active_cell_index()];
          for (unsigned int q = 0; q < n_q; ++q)
            {
              if (!material.admissible(grad_u[q], T[q]))
                {
                  admissible = 0.;
                  continue;
                }
              const double       JxW = fe_values.JxW(q);
              const Tensor<2, 2> P   = material.first_piola(grad_u[q], T[q]);
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  shape_gradients[i] = fe_values[u].gradient(i, q);
                  cell_rhs(i) -= scalar_product(P, shape_gradients[i]) * JxW;
                }
              if (with_matrix)
                {
                  const Tensor<4, 2> A = material.tangent(grad_u[q], T[q]);
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    tangent_times_gradient[j] =
                      double_contract_right(A, shape_gradients[j]);
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      cell_matrix(i, j) +=
                        scalar_product(shape_gradients[i],
                                       tangent_times_gradient[j]) *
                        JxW;
                }
            }
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() < traction_condition.size() &&
                traction_condition[cell->face(f)->boundary_id()] >= 0)
              {
                const auto &functions = traction_functions
                  [traction_condition[cell->face(f)->boundary_id()]];
                fe_face_values.reinit(cell, f);
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    const Point<2> &p = fe_face_values.quadrature_point(q);
                    Tensor<1, 2>    traction;
                    for (unsigned int d = 0; d < 2; ++d)
                      traction[d] = functions[d]->value(p);
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      cell_rhs(i) += traction * fe_face_values[u].value(i, q) *
                                     fe_face_values.JxW(q);
                  }
              }
          cell->get_dof_indices(dof_indices);
          if (with_matrix)
            constraints_used.distribute_local_to_global(cell_matrix,
                                                        cell_rhs,
                                                        dof_indices,
                                                        system_matrix,
                                                        system_rhs);
          else
            constraints_used.distribute_local_to_global(cell_rhs,
                                                        dof_indices,
                                                        system_rhs);
        }
    if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    return Utilities::MPI::min(admissible, communicator) > 0.;
  }

  double
  ThermoelasticSolver::residual_norm(
    const TrilinosWrappers::MPI::Vector &displacement)
  {
    if (!assemble(displacement, residual_constraints, false))
      return std::numeric_limits<double>::infinity();
    return system_rhs.l2_norm();
  }

  unsigned int
  ThermoelasticSolver::solve_linear_system(
    TrilinosWrappers::MPI::Vector &update)
  {
    update                = 0;
    const double rhs_norm = system_rhs.l2_norm();
    if (rhs_norm == 0.)
      return 0;
    TrilinosWrappers::PreconditionAMG                 amg;
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    std::vector<std::vector<bool>>                    constant_modes;
    DoFTools::extract_constant_modes(*dof_handler,
                                     ComponentMask(2, true),
                                     constant_modes);
    data.constant_modes        = constant_modes;
    data.elliptic              = true;
    data.higher_order_elements = fe->degree > 1;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    amg.initialize(system_matrix, data);
    SolverControl control(
      parameters.mechanics.linear_max_iterations,
      std::max(parameters.mechanics.linear_tolerance * rhs_norm, 1e-300));
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    try
      {
        cg.solve(system_matrix, update, system_rhs, amg);
      }
    catch (const SolverControl::NoConvergence &failure)
      {
        std::ostringstream message;
        message << "thermoelastic solver: CG did not converge in "
                << failure.last_step << " iterations (residual "
                << failure.last_residual << ", target " << control.tolerance()
                << "). Raise Mechanics/Linear solver maximum iterations, "
                   "loosen Mechanics/Linear solver tolerance, or check that "
                   "the boundary conditions remove the rigid-body motions "
                   "(Mechanics/Pinned points).";
        throw RunError(message.str());
      }
    total_linear_iterations += control.last_step();
    return control.last_step();
  }

  // ------------------------------------------------------------ Newton
  void
  ThermoelasticSolver::solve(const double time)
  {
    const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
    temperature_function->set_time(time);
    for (auto &functions : traction_functions)
      for (auto &function : functions)
        function->set_time(time);
    compute_quadrature_temperatures();

    double largest_modulus = 0.;
    for (const auto &material : materials)
      largest_modulus = std::max(largest_modulus, material.mu());
    const double round_off =
      1e-13 * 3. * largest_modulus * std::sqrt(domain_area);

    make_newton_constraints(time);
    double residual  = residual_norm(solution);
    double reference = std::isfinite(residual) ? residual : 0.;
    newton_history.push_back({time, 0, residual, 0., 0});
    if (root)
      std::cerr << "newton t = " << time << ": iteration 0, |R| = " << residual
                << " N/m" << std::endl;

    TrilinosWrappers::MPI::Vector update(locally_owned_dofs, communicator),
      trial(locally_owned_dofs, communicator);
    TrilinosWrappers::MPI::Vector trial_ghosted(locally_owned_dofs,
                                                locally_relevant_dofs,
                                                communicator);
    bool                          converged = false;
    for (unsigned int iteration = 1;
         iteration <= parameters.mechanics.newton_max_iterations;
         ++iteration)
      {
        const double boundary_increment = make_newton_constraints(time);
        if (!assemble(solution, newton_constraints, true))
          throw RunError("thermoelastic solver: an element is inverted (J <= "
                         "0) at t = " +
                         Utilities::to_string(time) +
                         " s; use smaller load steps (Time stepping/Time "
                         "step).");
        const unsigned int linear_iterations = solve_linear_system(update);
        newton_constraints.distribute(update);

        // backtracking: halve the step until the residual decreases (or,
        // while boundary values are still being applied, until no element
        // is inverted)
        double       step           = 1.;
        double       trial_residual = 0.;
        const double previous       = residual;
        for (unsigned int halving = 0; halving <= 10; ++halving)
          {
            trial = solution;
            trial.add(step, update);
            trial_ghosted  = trial;
            trial_residual = residual_norm(trial_ghosted);
            const bool acceptable =
              std::isfinite(trial_residual) &&
              (!parameters.mechanics.line_search || boundary_increment > 0. ||
               trial_residual < previous || trial_residual <= round_off);
            if (acceptable)
              break;
            if (halving == 10 || !parameters.mechanics.line_search)
              {
                if (!std::isfinite(trial_residual))
                  throw RunError(
                    "thermoelastic solver: every Newton step inverts an "
                    "element at t = " +
                    Utilities::to_string(time) +
                    " s; use smaller load steps (Time stepping/Time step).");
                break;
              }
            step *= 0.5;
          }
        solution  = trial_ghosted;
        residual  = trial_residual;
        reference = std::max(reference, residual);
        ++total_newton_iterations;
        newton_history.push_back(
          {time, iteration, residual, step, linear_iterations});
        if (root)
          std::cerr << "newton t = " << time << ": iteration " << iteration
                    << ", |R| = " << residual << " N/m, step " << step << ", "
                    << linear_iterations << " CG iterations" << std::endl;
        const bool boundary_reached = boundary_increment == 0. || step == 1.;
        if (boundary_reached &&
            (residual <= parameters.mechanics.newton_tolerance * reference ||
             residual <= round_off))
          {
            converged = true;
            break;
          }
      }
    ++solves;
    if (!converged)
      {
        write_summary(time);
        std::ostringstream message;
        message << "thermoelastic solver: Newton did not converge at t = "
                << time << " s within Mechanics/Newton maximum iterations = "
                << parameters.mechanics.newton_max_iterations << " (residual "
                << residual << " N/m, target "
                << std::max(parameters.mechanics.newton_tolerance * reference,
                            round_off)
                << " N/m). Raise the iteration limit, or use smaller load "
                   "steps (Time stepping/Time step).";
        throw RunError(message.str());
      }
  }

  // ------------------------------------------------------------ AMR
  void
  ThermoelasticSolver::adapt_mesh()
  {
    auto &distributed_triangulation =
      dynamic_cast<parallel::distributed::Triangulation<2> &>(*triangulation);
    mark_cells_by_kelly(distributed_triangulation,
                        *mapping,
                        *dof_handler,
                        solution,
                        fe->degree,
                        parameters.adaptivity,
                        coarse_level);
    parallel::distributed::SolutionTransfer<2, TrilinosWrappers::MPI::Vector>
      transfer(*dof_handler);
    triangulation->prepare_coarsening_and_refinement();
    transfer.prepare_for_coarsening_and_refinement(solution);
    triangulation->execute_coarsening_and_refinement();
    setup_dofs();
    TrilinosWrappers::MPI::Vector distributed(locally_owned_dofs, communicator);
    transfer.interpolate(distributed);
    hanging_node_constraints.distribute(distributed);
    solution = distributed;
  }

  // ------------------------------------------------------------ output
  std::vector<double>
  ThermoelasticSolver::monitor_values(
    const DoFHandler<2>::active_cell_iterator &cell,
    const Point<2>                            &unit_point) const
  {
    const Quadrature<2> quadrature(std::vector<Point<2>>{unit_point});
    FEValues<2>         fe_values(*mapping,
                          *fe,
                          quadrature,
                          update_values | update_gradients |
                            update_quadrature_points);
    fe_values.reinit(cell);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<1, 2>>        displacement(1);
    std::vector<Tensor<2, 2>>        grad_u(1);
    fe_values[u].get_function_values(solution, displacement);
    fe_values[u].get_function_gradients(solution, grad_u);
    const Triangulation<2>::active_cell_iterator tria_cell(triangulation,
                                                           cell->level(),
                                                           cell->index());
    const Point<2>            p = fe_values.quadrature_point(0);
    const std::vector<double> T = temperatures_at(tria_cell, {unit_point}, {p});
    const Tensor<2, 2>        sigma =
      materials[cell->material_id()].cauchy(grad_u[0], T[0]);
    std::vector<double> values = {T[0],
                                  displacement[0][0],
                                  displacement[0][1],
                                  sigma[0][0],
                                  sigma[1][1],
                                  sigma[0][1]};
    if (parameters.mechanics.polar_frame)
      {
        const Tensor<1, 2> radial = p - parameters.mechanics.polar_centre;
        const double       angle  = std::atan2(radial[1], radial[0]);
        const double       c = std::cos(angle), s = std::sin(angle);
        values.push_back(sigma[0][0] * c * c + sigma[1][1] * s * s +
                         2. * sigma[0][1] * c * s);
        values.push_back(sigma[0][0] * s * s + sigma[1][1] * c * c -
                         2. * sigma[0][1] * c * s);
      }
    return values;
  }

  void
  ThermoelasticSolver::write_output(const double time)
  {
    monitors->write(time,
                    *mapping,
                    *dof_handler,
                    [this](const DoFHandler<2>::active_cell_iterator &cell,
                           const Point<2> &unit_point) {
                      return monitor_values(cell, unit_point);
                    });

    // stress extremes over the quadrature points of the last solve
    const Quadrature<2> quadrature =
      uses_quadrilaterals() ? Quadrature<2>(QGauss<2>(fe->degree + 1)) :
                              Quadrature<2>(QGaussSimplex<2>(fe->degree + 1));
    FEValues<2> fe_values(*mapping, *fe, quadrature, update_gradients);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, 2>>        grad_u(quadrature.size());
    std::array<double, 5>            extremes = {{0.,
                                                  0.,
                                                  0.,
                                                  -std::numeric_limits<double>::max(),
                                                  std::numeric_limits<double>::max()}};
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[u].get_function_gradients(solution, grad_u);
          const auto &T = quadrature_temperatures[cell->active_cell_index()];
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Tensor<2, 2> s =
                materials[cell->material_id()].cauchy(grad_u[q], T[q]);
              const double mean = 0.5 * (s[0][0] + s[1][1]);
              const double radius =
                std::hypot(0.5 * (s[0][0] - s[1][1]), s[0][1]);
              extremes[0] = std::max(extremes[0], std::abs(s[0][0]));
              extremes[1] = std::max(extremes[1], std::abs(s[1][1]));
              extremes[2] = std::max(extremes[2], std::abs(s[0][1]));
              extremes[3] = std::max(extremes[3], mean + radius);
              extremes[4] = std::min(extremes[4], mean - radius);
            }
        }
    for (unsigned int k = 0; k < 4; ++k)
      stress_extremes[k] = Utilities::MPI::max(extremes[k], communicator);
    stress_extremes[4] = Utilities::MPI::min(extremes[4], communicator);

    if (parameters.output.write_vtu)
      {
        const bool with_szz =
          parameters.mechanics.idealisation ==
            MechanicsParameters::Idealisation::plane_strain &&
          parameters.mechanics.strain_measure ==
            MechanicsParameters::StrainMeasure::small;
        const ThermoelasticPostprocessor postprocessor(
          materials,
          *mapping,
          [this](const Triangulation<2>::active_cell_iterator &cell,
                 const std::vector<Point<2>>                  &unit_points,
                 const std::vector<Point<2>>                  &points) {
            return temperatures_at(cell, unit_points, points);
          },
          with_szz);
        DataOut<2> data_out;
        data_out.attach_dof_handler(*dof_handler);
        const std::vector<
          DataComponentInterpretation::DataComponentInterpretation>
          vector_field(
            2,
            DataComponentInterpretation::component_is_part_of_vector);
        data_out.add_data_vector(solution,
                                 std::vector<std::string>(2, "displacement"),
                                 DataOut<2>::type_dof_data,
                                 vector_field);
        data_out.add_data_vector(solution, postprocessor);
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
        data_out.build_patches(*mapping,
                               uses_quadrilaterals() ? fe->degree : 1);
        solution_series->write(data_out, time);
      }
    write_summary(time);
  }

  void
  ThermoelasticSolver::write_summary(const double time) const
  {
    const auto             &mechanics = parameters.mechanics;
    std::vector<JsonObject> history;
    for (const auto &record : newton_history)
      {
        JsonObject object;
        object.add("time", record.time)
          .add("iteration", record.iteration)
          .add("residual", record.residual)
          .add("step_length", record.step_length)
          .add("cg_iterations", record.linear_iterations);
        history.push_back(object);
      }
    JsonObject stress;
    stress.add("units", std::string("Pa, Cauchy, tension positive"))
      .add("max_abs_sxx", stress_extremes[0])
      .add("max_abs_syy", stress_extremes[1])
      .add("max_abs_sxy", stress_extremes[2])
      .add("max_principal", stress_extremes[3])
      .add("min_principal", stress_extremes[4]);
    const double    wall_time = wall_clock() - wall_start;
    const long long cells =
      static_cast<long long>(triangulation->n_global_active_cells());
    JsonObject summary;
    summary.add("model", parameters.model)
      .add("prm_file", parameters.prm_file)
      .add("mpi_processes", Utilities::MPI::n_mpi_processes(communicator))
      .add("idealisation",
           std::string(mechanics.idealisation ==
                           MechanicsParameters::Idealisation::plane_stress ?
                         "plane stress" :
                         "plane strain"))
      .add("strain_measure",
           std::string(mechanics.strain_measure ==
                           MechanicsParameters::StrainMeasure::small ?
                         "small" :
                         "finite"))
      .add("temperature_source",
           std::string(mechanics.temperature_source ==
                           MechanicsParameters::TemperatureSource::function ?
                         "function" :
                       mechanics.temperature_source ==
                           MechanicsParameters::TemperatureSource::heat_solver ?
                         "heat solver" :
                         "discrete heat"))
      .add("cells", cells)
      .add("dofs", static_cast<long long>(dof_handler->n_dofs()))
      .add("steps", static_cast<long long>(solves))
      .add("end_time", time)
      .add("wall_time", wall_time)
      .add("element_steps_per_second",
           wall_time > 0 ?
             cells * static_cast<double>(std::max(solves, 1ul)) / wall_time :
             0.)
      .add("newton_iterations", static_cast<long long>(total_newton_iterations))
      .add("linear_iterations", static_cast<long long>(total_linear_iterations))
      .add("broken_joints", 0u)
      .add("cracks", 0u)
      .add("stress", stress)
      .add("newton_history", history);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(parameters.output.directory + "/summary.json",
                            summary.str() + "\n");
  }

  // ------------------------------------------------------------ drivers
  void
  ThermoelasticSolver::check_input()
  {
    if (parameters.initial.stress_free)
      throw InputError(
        "Initial conditions/Stress free = true: the continuum thermoelastic "
        "model measures the thermal strain from each material's Reference "
        "temperature; allowed is false (set the Reference temperature "
        "instead).");
    if (parameters.mechanics.temperature_source ==
        MechanicsParameters::TemperatureSource::heat_solver)
      {
        Parameters heat_parameters = parameters;
        heat_parameters.model      = "continuum heat";
        heat_parameters.output.directory =
          parameters.output.directory + "/heat";
        heat_solver =
          std::make_unique<HeatSolver>(heat_parameters, communicator);
        heat_solver->check_input();
        create_output_folder(parameters.output.directory, communicator);
        setup(&heat_solver->get_triangulation());
      }
    else
      {
        setup();
        if (parameters.mechanics.temperature_source ==
            MechanicsParameters::TemperatureSource::discrete_heat)
          {
            if (parameters.adaptivity.enable)
              throw InputError(
                "Adaptive refinement/Enable = true: Mechanics/Temperature "
                "source = discrete heat keeps the mesh; allowed is false.");
            coupling::DiscreteHeatField check(parameters,
                                              *triangulation,
                                              communicator);
          }
      }
  }

  void
  ThermoelasticSolver::run()
  {
    if (parameters.resume)
      throw InputError(
        "--resume: the continuum models do not write checkpoints; run the "
        "case again without --resume (SIGINT/SIGTERM stop them cleanly with "
        "the outputs so far). Checkpoints are for the discrete models.");
    if (parameters.mechanics.temperature_source ==
        MechanicsParameters::TemperatureSource::heat_solver)
      run_with_heat_solver();
    else
      run_with_temperature_function();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cout << "done: " << solves << " solves, " << total_newton_iterations
                << " Newton iterations, " << total_linear_iterations
                << " CG iterations, " << triangulation->n_global_active_cells()
                << " cells, " << dof_handler->n_dofs() << " dofs, "
                << wall_clock() - wall_start << " s wall" << std::endl;
  }

  void
  ThermoelasticSolver::run_with_temperature_function()
  {
    setup();
    // Temperature source = discrete heat: the discrete layer's heat on this
    // mesh, advanced to the time of every solve
    std::unique_ptr<coupling::DiscreteHeatField> discrete_heat;
    if (parameters.mechanics.temperature_source ==
        MechanicsParameters::TemperatureSource::discrete_heat)
      {
        discrete_heat =
          std::make_unique<coupling::DiscreteHeatField>(parameters,
                                                        *triangulation,
                                                        communicator);
        set_temperature(discrete_heat->field());
      }
    const auto solve_at = [&](const double time) {
      if (discrete_heat)
        discrete_heat->advance_to(time);
      solve(time);
    };
    const auto &time_parameters = parameters.time;
    if (time_parameters.mode == TimeSteppingParameters::Mode::steady)
      {
        const double       time     = time_parameters.start_time;
        const unsigned int n_cycles = parameters.adaptivity.enable ?
                                        parameters.adaptivity.steady_cycles :
                                        1;
        for (unsigned int cycle = 0; cycle < n_cycles; ++cycle)
          {
            if (cycle > 0)
              adapt_mesh();
            solve_at(time);
            if (Utilities::MPI::this_mpi_process(communicator) == 0)
              std::cout << "cycle " << cycle << ": "
                        << triangulation->n_global_active_cells() << " cells, "
                        << dof_handler->n_dofs() << " dofs" << std::endl;
          }
        write_output(time);
        return;
      }

    // quasi-static load steps at every time step; outputs at the output
    // times (the step is shortened to land on them) and at the end
    const double start                 = time_parameters.start_time,
                 end                   = time_parameters.end_time;
    const double        time_tolerance = 1e-10 * std::max(1., std::abs(end));
    std::vector<double> output_times;
    for (const double t : parameters.output.times)
      if (t > start + time_tolerance && t < end - time_tolerance)
        output_times.push_back(t);
    if (parameters.output.interval > 0)
      for (double t = start + parameters.output.interval;
           t < end - time_tolerance;
           t += parameters.output.interval)
        output_times.push_back(t);
    output_times.push_back(end);
    std::sort(output_times.begin(), output_times.end());

    ProgressReporter progress(parameters.output.progress_interval,
                              start,
                              end,
                              Utilities::MPI::this_mpi_process(communicator) ==
                                0);
    double           time = start;
    unsigned long    step = 0;
    solve_at(time);
    write_output(time);
    for (const double output_time : output_times)
      while (time < output_time - time_tolerance)
        {
          double dt = time_parameters.time_step;
          if (time + dt > output_time - 1e-3 * dt)
            dt = output_time - time;
          time = std::abs(time + dt - output_time) < time_tolerance ?
                   output_time :
                   time + dt;
          solve_at(time);
          ++step;
          if (std::abs(time - output_time) < time_tolerance)
            write_output(output_time);
          if (parameters.adaptivity.enable &&
              step % parameters.adaptivity.interval == 0 &&
              time < end - time_tolerance)
            adapt_mesh();
          progress.update(step, time);
          if (stop_requested_on_any_rank(communicator))
            {
              if (std::abs(time - output_time) >= time_tolerance)
                write_output(time);
              throw StopRequested("stopped by " + stop_signal_name() +
                                  " at t = " + Utilities::to_string(time) +
                                  " s after step " + std::to_string(step) +
                                  "; outputs so far in " +
                                  parameters.output.directory +
                                  " (continuum runs cannot be resumed).");
            }
        }
  }

  void
  ThermoelasticSolver::run_with_heat_solver()
  {
    Parameters heat_parameters       = parameters;
    heat_parameters.model            = "continuum heat";
    heat_parameters.output.directory = parameters.output.directory + "/heat";
    heat_solver = std::make_unique<HeatSolver>(heat_parameters, communicator);
    create_output_folder(parameters.output.directory, communicator);
    heat_solver->set_output_hook([this](const double time) {
      if (!dof_handler)
        setup(&heat_solver->get_triangulation());
      else if (mesh_changed)
        {
          // the heat solver adapted the shared mesh: start from rest
          setup_dofs();
          solution = 0;
        }
      set_temperature(heat_solver->get_dof_handler(),
                      heat_solver->get_mapping(),
                      heat_solver->get_temperature());
      solve(time);
      write_output(time);
    });
    heat_solver->run();
  }
} // namespace tmfdem
