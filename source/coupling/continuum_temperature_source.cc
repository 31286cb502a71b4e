#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/continuum/heat_solver.h>
#include <tmfdem/coupling/continuum_temperature_source.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/io/checkpoint.h>

namespace tmfdem
{
  namespace coupling
  {
    namespace
    {
      const bool registered = discrete::register_temperature_source(
        "continuum heat",
        "the deal.II continuum heat solver on the same triangle mesh "
        "(FE_SimplexP of Heat solver/Degree, theta scheme of Time "
        "stepping/Method, Trilinos AMG), its field projected onto the linear "
        "field of every triangle at every thermal step; conducts across "
        "broken joints, no contact heat",
        [](const Parameters        &parameters,
           discrete::DiscreteModel &model,
           MPI_Comm                 communicator)
          -> std::unique_ptr<discrete::TemperatureSource> {
          return std::make_unique<ContinuumTemperatureSource>(parameters,
                                                              model,
                                                              communicator);
        });

      /** The parameters of the continuum heat solver: those of the run,
       *  with the model renamed and no monitors of its own. */
      Parameters
      continuum_heat_parameters(const Parameters &parameters)
      {
        if (parameters.get<DiscreteHeatParameters>().time_integration !=
            DiscreteHeatParameters::TimeIntegration::implicit)
          throw InputError(
            "Discrete heat/Time integration = " +
            parameters.get<DiscreteHeatParameters>().time_integration_name() +
            " applies to the discrete heat; Temperature source = continuum "
            "heat integrates with the theta scheme of Time stepping/Method; "
            "allowed is implicit (the default).");
        Parameters heat = parameters;
        heat.model      = "continuum heat";
        heat.monitors   = MonitorParameters();
        return heat;
      }

      /** The vertex coordinates of a triangle, sorted (a key that does not
       *  depend on the vertex order). */
      std::array<double, 6>
      triangle_key(std::array<std::pair<double, double>, 3> vertices)
      {
        std::sort(vertices.begin(), vertices.end());
        return {{vertices[0].first,
                 vertices[0].second,
                 vertices[1].first,
                 vertices[1].second,
                 vertices[2].first,
                 vertices[2].second}};
      }
    } // namespace

    ContinuumTemperatureSource::ContinuumTemperatureSource(
      const Parameters        &parameters,
      discrete::DiscreteModel &model,
      MPI_Comm                 communicator)
      : heat_parameters(continuum_heat_parameters(parameters))
      , model(model)
      , communicator(communicator)
      , heat_solver(
          std::make_unique<HeatSolver<2>>(heat_parameters, communicator))
    {}

    ContinuumTemperatureSource::~ContinuumTemperatureSource() = default;

    std::string
    ContinuumTemperatureSource::describe() const
    {
      const DoFHandler<2> &dofs = heat_solver->get_dof_handler();
      return "continuum heat, FE_SimplexP(" +
             std::to_string(dofs.get_fe().degree) + "), " +
             std::to_string(dofs.n_dofs()) + " DoFs, " +
             heat_parameters.time.method +
             " (conducts across broken joints, no contact heat)";
    }

    double
    ContinuumTemperatureSource::stable_time_step() const
    {
      return std::numeric_limits<double>::infinity();
    }

    FullMatrix<double>
    ContinuumTemperatureSource::projection_to_linear(const unsigned int degree)
    {
      const FE_SimplexP<2> linear(1), field(degree);
      const unsigned int   n = field.n_dofs_per_cell();
      // exact for the products of P1 and P(degree <= 3) functions
      const QGaussSimplex<2> quadrature(3);
      FullMatrix<double>     mass(3, 3), mixed(3, n);
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const Point<2> &p = quadrature.point(q);
          const double    w = quadrature.weight(q);
          for (unsigned int i = 0; i < 3; ++i)
            {
              const double phi_i = linear.shape_value(i, p);
              for (unsigned int j = 0; j < 3; ++j)
                mass(i, j) += w * phi_i * linear.shape_value(j, p);
              for (unsigned int j = 0; j < n; ++j)
                mixed(i, j) += w * phi_i * field.shape_value(j, p);
            }
        }
      FullMatrix<double> inverse(3, 3), result(3, n);
      inverse.invert(mass);
      inverse.mmult(result, mixed);
      return result;
    }

    void
    ContinuumTemperatureSource::initialise(const double time)
    {
      heat_solver->prepare_coupled_stepping();
      if (std::abs(time - heat_solver->current_time()) >
          1e-12 * std::max(1., std::abs(time)))
        throw InputError("continuum heat source: initialised at t = " +
                         Utilities::to_string(time) +
                         " s, not at Time stepping/Start time.");
      const DoFHandler<2> &dofs = heat_solver->get_dof_handler();
      const unsigned int   n    = dofs.get_fe().n_dofs_per_cell();
      if (dofs.get_triangulation().n_active_cells() != model.n_elements)
        throw InputError(
          "continuum heat source: the continuum mesh has " +
          std::to_string(dofs.get_triangulation().n_active_cells()) +
          " triangles, the discrete layer " + std::to_string(model.n_elements) +
          "; they must be the same mesh.");
      projection = projection_to_linear(dofs.get_fe().degree);

      // match the continuum cells to the discrete triangles by their
      // vertex coordinates (both meshes come from the same Mesh subsection)
      std::map<std::array<double, 6>, DoFHandler<2>::active_cell_iterator>
        cell_at;
      for (const auto &cell : dofs.active_cell_iterators())
        {
          std::array<std::pair<double, double>, 3> vertices;
          for (unsigned int v = 0; v < 3; ++v)
            vertices[v] = {cell->vertex(v)[0], cell->vertex(v)[1]};
          cell_at.emplace(triangle_key(vertices), cell);
        }
      element_dofs.resize(model.n_elements * n);
      node_vertex.resize(model.n_nodes);
      std::vector<types::global_dof_index> cell_dofs(n);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          std::array<std::pair<double, double>, 3> vertices;
          for (unsigned int k = 0; k < 3; ++k)
            vertices[k] = {model.x_ref[3 * e + k], model.y_ref[3 * e + k]};
          const auto found = cell_at.find(triangle_key(vertices));
          if (found == cell_at.end())
            throw InputError(
              "continuum heat source: discrete triangle " + std::to_string(e) +
              " at (" + Utilities::to_string(vertices[0].first) + ", " +
              Utilities::to_string(vertices[0].second) +
              ") has no continuum cell with the same vertices; the two "
              "layers must use the same mesh.");
          const auto &cell = found->second;
          cell->get_dof_indices(cell_dofs);
          std::copy(cell_dofs.begin(),
                    cell_dofs.end(),
                    element_dofs.begin() + std::size_t(e) * n);
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int v = 0; v < 3; ++v)
              if (cell->vertex(v)[0] == vertices[k].first &&
                  cell->vertex(v)[1] == vertices[k].second)
                node_vertex[3 * e + k] = v;
        }
      nodal_temperature.reinit(model.n_nodes);
      transfer();
      copy_balance();
    }

    void
    ContinuumTemperatureSource::step(const double time, const double time_step)
    {
      (void)time;
      const std::map<types::boundary_id, double> before =
        heat_solver->heat_balance().boundary_heat_in;
      if (heat_solver->in_rannacher_start())
        {
          // a Crank-Nicolson run starts with backward Euler half steps
          heat_solver->advance(0.5 * time_step);
          heat_solver->advance(time_step - 0.5 * time_step);
        }
      else
        heat_solver->advance(time_step);
      transfer();
      copy_balance();
      last_rate.clear();
      for (const auto &[id, heat] : heat_balance.boundary_heat_in)
        {
          const auto   old   = before.find(id);
          const double start = old == before.end() ? 0. : old->second;
          last_rate[id]      = (heat - start) / time_step;
        }
    }

    void
    ContinuumTemperatureSource::transfer()
    {
      // the field on every rank: each rank projects all triangles (the
      // discrete layer reads this source replicated, partition.h)
      all_temperatures        = Vector<double>(heat_solver->get_temperature());
      const Vector<double> &u = all_temperatures;
      const unsigned int    n = projection.n();
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const types::global_dof_index *dofs =
            element_dofs.data() + std::size_t(e) * n;
          for (unsigned int k = 0; k < 3; ++k)
            {
              const unsigned int v     = node_vertex[3 * e + k];
              double             value = 0.;
              for (unsigned int j = 0; j < n; ++j)
                value += projection(v, j) * u(dofs[j]);
              nodal_temperature[3 * e + k] = value;
            }
        }
    }

    void
    ContinuumTemperatureSource::copy_balance()
    {
      const auto &b                 = heat_solver->heat_balance();
      heat_balance.boundary_heat_in = b.boundary_heat_in;
      heat_balance.source_heat      = b.source_heat;
      heat_balance.stored_heat      = b.stored_heat;
      heat_balance.contact_heat     = 0.;
      heat_balance.contact_exchange = 0.;
    }

    void
    ContinuumTemperatureSource::save(CheckpointWriter &out) const
    {
      // (rank 0 alone writes checkpoints: the copy of the last transfer())
      std::vector<double> values(all_temperatures.begin(),
                                 all_temperatures.end());
      out.put(heat_solver->current_time());
      out.put<std::uint64_t>(heat_solver->steps_taken());
      out.put(values);
      const auto &b = heat_solver->heat_balance();
      out.put(b.boundary_heat_in);
      out.put(b.source_heat);
      out.put(b.stored_heat);
      out.put(last_rate);
    }

    void
    ContinuumTemperatureSource::load(CheckpointReader &in)
    {
      double        time  = 0.;
      std::uint64_t steps = 0;
      in.get(time);
      in.get(steps);
      std::vector<double> values;
      in.get(values, heat_solver->get_dof_handler().n_dofs());
      HeatSolver<2>::HeatBalance balance;
      in.get(balance.boundary_heat_in);
      in.get(balance.source_heat);
      in.get(balance.stored_heat);
      in.get(last_rate);
      heat_solver->restore_state(time, steps, balance, values);
      transfer();
      copy_balance();
    }
  } // namespace coupling
} // namespace tmfdem
