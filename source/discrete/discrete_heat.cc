#include <algorithm>
#include <cmath>
#include <set>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/contact.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_heat.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/heat_kernel.h>
#include <tmfdem/discrete/partition.h>
#include <tmfdem/io/checkpoint.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      const bool registered = register_temperature_source(
        "discrete heat",
        "the discrete layer's own heat conduction: P1 in every triangle, "
        "conducting joints that stop conducting when they break, contact "
        "heat, boundary conditions (Discrete heat subsection)",
        [](const Parameters &parameters,
           DiscreteModel    &model,
           MPI_Comm) -> std::unique_ptr<TemperatureSource> {
          return std::make_unique<DiscreteHeat>(parameters, model);
        });
    } // namespace

    namespace
    {
      /** Gradients of the P1 shape functions times 2A (current geometry)
       *  and the current area A [m^2]. */
      inline double
      shape_gradients(const DiscreteModel &m,
                      const unsigned int   e,
                      double               g[3][2])
      {
        const double *const nodes[2] = {&m.x[3 * e], &m.y[3 * e]};
        double              G[3][2];
        scaled_shape_gradients<2>(nodes, G);
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int i = 0; i < 2; ++i)
            g[a][i] = G[a][i];
        return simplex_measure<2>(nodes);
      }

      /** Conductivity matrix K_ab = k A grad N_a . grad N_b of element e
       *  (heat_kernel.h). */
      inline void
      conductivity_matrix(const DiscreteModel &m,
                          const unsigned int   e,
                          const double         k,
                          double               K[3][3])
      {
        const double *const nodes[2] = {&m.x[3 * e], &m.y[3 * e]};
        double              Ke[3][3];
        discrete::conductivity_matrix<2, double>(nodes, k, Ke);
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            K[a][b] = Ke[a][b];
      }

      /**
       * Anisotropic conductivity matrix K_ab = A grad N_a . D grad N_b of
       * element e (paper Eqs. 8-9, 18-20), D the reference tensor @p D
       * (xx, xy, yy) [W/(m K)] turned with the element's rotation R from
       * the reference to the current configuration, D' = R D R^T (R from
       * the polar decomposition of the element's deformation gradient F:
       * its angle is atan2(F_10 - F_01, F_00 + F_11)).
       */
      inline void
      conductivity_matrix(const DiscreteModel         &m,
                          const unsigned int           e,
                          const std::array<double, 3> &D,
                          double                       K[3][3])
      {
        double       g[3][2];
        const double area = shape_gradients(m, e, g);
        // F = [current edges] [reference edges]^-1
        const double *x = &m.x[3 * e], *y = &m.y[3 * e];
        const double *X = &m.x_ref[3 * e], *Y = &m.y_ref[3 * e];
        const double  c00 = x[1] - x[0], c01 = x[2] - x[0];
        const double  c10 = y[1] - y[0], c11 = y[2] - y[0];
        const double  r00 = X[1] - X[0], r01 = X[2] - X[0];
        const double  r10 = Y[1] - Y[0], r11 = Y[2] - Y[0];
        const double  det   = r00 * r11 - r01 * r10;
        const double  F00   = (c00 * r11 - c01 * r10) / det;
        const double  F01   = (-c00 * r01 + c01 * r00) / det;
        const double  F10   = (c10 * r11 - c11 * r10) / det;
        const double  F11   = (-c10 * r01 + c11 * r00) / det;
        const double  angle = std::atan2(F10 - F01, F00 + F11);
        const double  c = std::cos(angle), s = std::sin(angle);
        // D' = R D R^T, R = [[c, -s], [s, c]]
        const double dxx   = c * c * D[0] - 2. * c * s * D[1] + s * s * D[2];
        const double dyy   = s * s * D[0] + 2. * c * s * D[1] + c * c * D[2];
        const double dxy   = c * s * (D[0] - D[2]) + (c * c - s * s) * D[1];
        const double scale = 1. / (4. * area);
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            K[a][b] = scale * (g[a][0] * (dxx * g[b][0] + dxy * g[b][1]) +
                               g[a][1] * (dxy * g[b][0] + dyy * g[b][1]));
      }
    } // namespace

    void
    DiscreteHeat::element_conductivity_matrix(const unsigned int e,
                                              double             K[3][3]) const
    {
      if (anisotropic[e])
        conductivity_matrix(model, e, conductivity_tensor[e], K);
      else
        conductivity_matrix(model, e, conductivity[e], K);
      if (conduction_m_matrix)
        make_conduction_m_matrix(K);
    }

    DiscreteHeat::DiscreteHeat(const Parameters &parameters,
                               DiscreteModel    &model)
      : parameters(parameters)
      , model(model)
    {
      const auto &dh = parameters.get<DiscreteHeatParameters>();
      use_implicit   = dh.time_integration ==
                     DiscreteHeatParameters::TimeIntegration::implicit;
      lumped_implicit_capacity = dh.lumped_implicit_capacity;
      conduction_m_matrix      = dh.conduction_m_matrix;
      beta                     = dh.joint_conductance_factor;
      contact_conductance      = dh.contact_conductance;
      T.reinit(model.n_nodes);

      conductivity.resize(model.n_elements);
      max_conductivity.resize(model.n_elements);
      anisotropic.assign(model.n_elements, 0);
      conductivity_tensor.resize(model.n_elements);
      volumetric_heat_capacity.resize(model.n_elements);
      lumped_capacity.assign(model.n_nodes, 0.);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const MaterialProperties &m = parameters.materials[model.material[e]];
          conductivity[e]             = m.thermal_conductivity;
          max_conductivity[e]         = m.max_conductivity();
          anisotropic[e]              = m.anisotropic_conductivity;
          const Tensor<2, 2> D        = m.conductivity_tensor();
          conductivity_tensor[e]      = {{D[0][0], D[0][1], D[1][1]}};
          volumetric_heat_capacity[e] = m.density * m.specific_heat;
          for (unsigned int k = 0; k < 3; ++k)
            lumped_capacity[3 * e + k] =
              volumetric_heat_capacity[e] * model.reference_area[e] / 3.;
        }
      // joints: k_i = beta k / h per unit area, half the edge to each node
      // pair: G = k_i h / 2 = beta k / 2 with k the harmonic mean of the
      // two sides' normal conductivities n.K.n (n the joint's unit normal
      // in the reference configuration; k itself where isotropic)
      joint_conductance.resize(model.n_joints);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          const unsigned int n0 = model.joint_nodes[4 * j];
          const unsigned int n1 = model.joint_nodes[4 * j + 1];
          const double       dx = model.x_ref[n1] - model.x_ref[n0];
          const double       dy = model.y_ref[n1] - model.y_ref[n0];
          const double       L  = std::hypot(dx, dy);
          const Tensor<1, 2> normal({dy / L, -dx / L});
          const auto         side_conductivity = [&](const unsigned int e) {
            return anisotropic[e] ? parameters.materials[model.material[e]]
                                      .normal_conductivity(normal) :
                                            conductivity[e];
          };
          const double ka = side_conductivity(model.joint_elements[2 * j]);
          const double kb = side_conductivity(model.joint_elements[2 * j + 1]);
          const double k  = 2. * ka * kb / (ka + kb);
          joint_conductance[j] =
            joint_pair_conductance<2>(beta, k, L, model.joint_length[j]);
        }

      // sources per material
      sources.resize(256);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        if (!sources[model.material[e]])
          sources[model.material[e]] = make_expression_function(
            parameters.materials[model.material[e]].heat_source,
            "Materials/Material " + std::to_string(model.material[e]) +
              "/Volumetric heat source");

      // boundary conditions
      std::vector<int> condition_of_id(256, -1);
      for (const auto &c : parameters.thermal_boundary.conditions)
        {
          ConditionFunctions f;
          f.type = c.type;
          f.temperature =
            make_expression_function(c.temperature, c.name + "/Temperature");
          f.flux = make_expression_function(c.heat_flux, c.name + "/Heat flux");
          f.coefficient =
            make_expression_function(c.heat_transfer_coefficient,
                                     c.name + "/Heat transfer coefficient");
          f.ambient = make_expression_function(c.ambient_temperature,
                                               c.name + "/Ambient temperature");
          model.check_boundary_ids(c.name + "/Boundary ids", c.boundary_ids);
          for (const auto id : c.boundary_ids)
            condition_of_id[id] = conditions.size();
          conditions.push_back(std::move(f));
        }
      dirichlet_node.assign(model.n_nodes, false);
      dirichlet_condition.assign(model.n_nodes, 0);
      std::map<unsigned int, unsigned int> dirichlet_vertex;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int k = 0; k < 3; ++k)
          {
            const types::boundary_id id = model.edge_boundary[3 * e + k];
            heat_balance.boundary_heat_in[id] += 0.;
            if (id == numbers::internal_face_boundary_id ||
                condition_of_id[id] < 0)
              continue;
            const unsigned int c = condition_of_id[id];
            boundary_edges.push_back({e, k, c, id});
            if (conditions[c].type == ThermalBoundaryCondition::Type::dirichlet)
              for (const unsigned int n : {3 * e + k, 3 * e + (k + 1) % 3})
                dirichlet_vertex[model.node_vertex[n]] = c;
          }
      heat_balance.boundary_heat_in.erase(numbers::internal_face_boundary_id);
      // every node on a Dirichlet vertex is held, not only those of the
      // elements that own the boundary edge
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          const auto it = dirichlet_vertex.find(model.node_vertex[n]);
          if (it != dirichlet_vertex.end())
            {
              dirichlet_node[n]      = true;
              dirichlet_condition[n] = it->second;
            }
        }
      for (const auto &[id, heat] : heat_balance.boundary_heat_in)
        {
          const unsigned int slot = balance_slot.size();
          balance_slot[id]        = slot;
        }
      // one rank: everything is this rank's (distribute() narrows it)
      first_element = 0;
      end_element   = model.n_elements;
      local_joints.resize(model.n_joints);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        local_joints[j] = j;
      first_edge = 0;
      end_edge   = boundary_edges.size();
      n_chunks   = (model.n_elements + chunk_elements - 1) / chunk_elements;
    }

    bool
    DiscreteHeat::distribute(ElementPartition &p)
    {
      partition      = &p;
      chunk_elements = p.chunk_size();
      n_chunks       = (model.n_elements + chunk_elements - 1) / chunk_elements;
      first_element  = p.begin();
      end_element    = p.end();
      Assert(first_element % chunk_elements == 0, ExcInternalError());
      // the joints with a triangle here: earlier ranks' joints to our
      // triangles, then our own (joints are numbered by their first
      // triangle), ascending
      local_joints = p.joints().others;
      for (unsigned int j = p.joints().begin; j < p.joints().end; ++j)
        local_joints.push_back(j);
      // boundary edges were made in triangle order
      const auto edge_of = [&](const unsigned int e) {
        return static_cast<std::size_t>(
          std::lower_bound(boundary_edges.begin(),
                           boundary_edges.end(),
                           e,
                           [](const BoundaryEdge &b, const unsigned int e) {
                             return b.element < e;
                           }) -
          boundary_edges.begin());
      };
      first_edge = edge_of(first_element);
      end_edge   = edge_of(end_element);
      rows.clear_pattern(); // the rows of the matrix change
      return true;
    }

    unsigned int
    DiscreteHeat::n_contact_pairs() const
    {
      unsigned int n = 0;
      for (const auto &[c, t] : contact_pairs)
        n += c >= first_element && c < end_element ? 1 : 0;
      return n;
    }

    void
    DiscreteHeat::reduce_chunks(std::vector<double> &partials,
                                const unsigned int   width,
                                std::vector<double> &totals) const
    {
      sum_chunks_in_order(partials, width, n_chunks, partition, totals);
    }

    DiscreteHeat::~DiscreteHeat() = default;

    void
    DiscreteHeat::set_function_time(const double time) const
    {
      for (const auto &f : conditions)
        {
          f.temperature->set_time(time);
          f.flux->set_time(time);
          f.coefficient->set_time(time);
          f.ambient->set_time(time);
        }
      for (const auto &s : sources)
        if (s)
          s->set_time(time);
    }

    void
    DiscreteHeat::initialise(const double time)
    {
      if (!parameters.has_local_initial_temperature())
        {
          auto initial =
            make_expression_function(parameters.initial.temperature,
                                     "Initial conditions/Temperature");
          initial->set_time(time);
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            T[n] = initial->value(Point<2>(model.x_ref[n], model.y_ref[n]));
        }
      else
        {
          // per material id (body > material > global): each triangle owns
          // its three nodes, so the value of its own entry is exact
          std::map<types::material_id, std::unique_ptr<FunctionParser<2>>>
            initial_of;
          for (unsigned int e = 0; e < model.n_elements; ++e)
            {
              auto &f = initial_of[model.material[e]];
              if (!f)
                {
                  const InitialTemperatureEntry entry =
                    parameters.initial_temperature_of(model.material[e]);
                  f = make_expression_function(entry.expression, entry.entry);
                  f->set_time(time);
                }
              for (unsigned int k = 0; k < 3; ++k)
                {
                  const unsigned int n = 3 * e + k;
                  T[n] = f->value(Point<2>(model.x_ref[n], model.y_ref[n]));
                }
            }
        }
      // Dirichlet nodes too start at the initial temperature; their values
      // act from the first step on. Held at t = 0 they would add, with the
      // consistent capacity of the implicit path, the heat of a hat
      // function at a heated edge (1.35 C of error at t = 2 s in paper 5.1
      // at h = 0.05 m instead of 0.68 C); from the initial temperature the
      // first backward Euler step equals one from the L2 projection of the
      // initial data onto the constrained space
      // (doc/cases/plate_transient.md)
      set_function_time(time);
      initial_T = T;
      update_contact_pairs();
    }

    void
    DiscreteHeat::set_dirichlet_values(const double time)
    {
      set_function_time(time);
      for (unsigned int n = 3 * first_element; n < 3 * end_element; ++n)
        if (dirichlet_node[n])
          T[n] = conditions[dirichlet_condition[n]].temperature->value(
            Point<2>(model.x_ref[n], model.y_ref[n]));
    }

    double
    DiscreteHeat::stable_time_step() const
    {
      // Gershgorin: lambda_max <= max_i (2 K_ii + 2 sum G + h L/2) / C_i,
      // over this rank's nodes, then the largest over the ranks (exact)
      std::vector<double> row(model.n_nodes, 0.);
      for (unsigned int e = first_element; e < end_element; ++e)
        {
          // with anisotropy the largest principal value: K(D) <= K(k_max I)
          // in the order of symmetric matrices, so the bound holds
          double K[3][3];
          conductivity_matrix(model, e, max_conductivity[e], K);
          if (conduction_m_matrix)
            make_conduction_m_matrix(K);
          for (unsigned int a = 0; a < 3; ++a)
            row[3 * e + a] += 2. * K[a][a];
        }
      for (const unsigned int j : local_joints)
        for (unsigned int s = 0; s < 4; ++s)
          row[model.joint_nodes[4 * j + s]] += 2. * joint_conductance[j];
      for_each_contact_transfer([&](const unsigned int         c,
                                    const unsigned int         t,
                                    const ContactHeatTransfer &transfer) {
        for (unsigned int k = 0; k < 3; ++k)
          {
            row[3 * c + k] +=
              2. * transfer.conductance * transfer.contactor_shape[k];
            row[3 * t + k] +=
              2. * transfer.conductance * transfer.target_shape[k];
          }
        if (parameters.get<DiscreteHeatParameters>().contact_heat_model ==
            ContactHeatModel::paper_literal)
          {
            // Jacobian s_i dQ/dT_j, s = (N_c, -N_t): row sums of |.|
            double weights = 0.;
            for (const double a : transfer.flow_weights)
              weights += std::abs(a);
            for (unsigned int k = 0; k < 3; ++k)
              {
                row[3 * c + k] += transfer.contactor_shape[k] * weights;
                row[3 * t + k] += transfer.target_shape[k] * weights;
              }
          }
      });
      set_function_time(0.);
      for_each_boundary_node(
        [](const ThermalBoundaryCondition::Type type) {
          return type == ThermalBoundaryCondition::Type::robin;
        },
        [&](const BoundaryEdge &b, const unsigned int n, const double half) {
          row[n] += half * conditions[b.condition].coefficient->value(
                             Point<2>(model.x_ref[n], model.y_ref[n]));
        });
      double lambda = 0.;
      for (unsigned int n = 3 * first_element; n < 3 * end_element; ++n)
        if (!dirichlet_node[n])
          lambda = std::max(lambda, row[n] / lumped_capacity[n]);
      if (partition != nullptr)
        lambda = partition->max(lambda);
      return lambda > 0. ? 2. / lambda : 1e300;
    }

    void
    DiscreteHeat::heat_rates(const double         time,
                             Vector<double>      &rate,
                             std::vector<double> &partials) const
    {
      rate.reinit(model.n_nodes);
      const unsigned int W     = balance_width();
      tbb::task_arena   &arena = arena_for(n_threads);
      // conduction inside this rank's triangles (each writes its own nodes)
      for_each_chunk(
        arena,
        end_element - first_element,
        512,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t e = first_element + begin; e < first_element + end;
               ++e)
            {
              double K[3][3];
              element_conductivity_matrix(e, K);
              for (unsigned int a = 0; a < 3; ++a)
                {
                  double q = 0.;
                  for (unsigned int b = 0; b < 3; ++b)
                    q -= K[a][b] * T[3 * e + b];
                  rate[3 * e + a] += q;
                }
            }
        });
      // intact joints with a triangle here: fluxes in parallel, added in
      // joint order (every node sees its joints in the order of one rank)
      std::vector<double> joint_flux(2 * local_joints.size());
      for_each_chunk(
        arena,
        local_joints.size(),
        512,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t i = begin; i < end; ++i)
            {
              const unsigned int j = local_joints[i];
              if (model.joint_status[j] == JointStatus::intact)
                for (unsigned int side = 0; side < 2; ++side)
                  {
                    const unsigned int a = model.joint_nodes[4 * j + side];
                    const unsigned int b = model.joint_nodes[4 * j + 2 + side];
                    joint_flux[2 * i + side] =
                      joint_conductance[j] * (T[b] - T[a]);
                  }
            }
        });
      for (std::size_t i = 0; i < local_joints.size(); ++i)
        if (model.joint_status[local_joints[i]] == JointStatus::intact)
          for (unsigned int end = 0; end < 2; ++end)
            {
              const unsigned int j = local_joints[i];
              const unsigned int a = model.joint_nodes[4 * j + end];
              const unsigned int b = model.joint_nodes[4 * j + 2 + end];
              const double       q = joint_flux[2 * i + end];
              rate[a] += q;
              rate[b] -= q;
            }
      // contact heat over overlaps (nodal heats of a pair sum to zero)
      add_contact_heat(rate, &partials);
      // sources
      set_function_time(time);
      for (unsigned int e = first_element; e < end_element; ++e)
        {
          const double  *x = &model.x_ref[3 * e], *y = &model.y_ref[3 * e];
          const Point<2> centroid((x[0] + x[1] + x[2]) / 3.,
                                  (y[0] + y[1] + y[2]) / 3.);
          const double   s = sources[model.material[e]]->value(centroid);
          if (s != 0.)
            {
              const double q = s * model.reference_area[e] / 3.;
              for (unsigned int a = 0; a < 3; ++a)
                rate[3 * e + a] += q;
              partials[chunk_of(e) * W + 1] += 3. * q;
            }
        }
      // Neumann and Robin, lumped on the edge's two nodes
      for_each_boundary_node(
        flux_condition,
        [&](const BoundaryEdge &b, const unsigned int n, const double half) {
          const auto    &f = conditions[b.condition];
          const Point<2> p(model.x_ref[n], model.y_ref[n]);
          const double   q =
            f.type == ThermalBoundaryCondition::Type::neumann ?
                half * f.flux->value(p) :
                half * f.coefficient->value(p) * (f.ambient->value(p) - T[n]);
          rate[n] += q;
          partials[chunk_of(b.element) * W + 3 + balance_slot.at(b.id)] += q;
        });
    }

    void
    DiscreteHeat::step(const double time, const double time_step)
    {
      // the ghosts' temperatures (new ghosts after a contact search too)
      if (partition != nullptr)
        partition->exchange_ghost_node_values(T.begin());
      const Vector<double> T_old = T;
      Vector<double>       rate;
      const unsigned int   W = balance_width();
      std::vector<double>  partials(n_chunks * W, 0.);
      // the paper's contact term is not a conductance (its Jacobian is
      // neither symmetric nor definite, heat_jacobian() is zero): the
      // implicit step takes it at the start of the step, T = T_old
      const bool lagged_contact =
        use_implicit &&
        parameters.get<DiscreteHeatParameters>().contact_heat_model ==
          ContactHeatModel::paper_literal;
      Vector<double>      lagged_contact_heat;
      std::vector<double> lagged_partials;
      if (lagged_contact)
        {
          lagged_contact_heat.reinit(model.n_nodes);
          lagged_partials.assign(n_chunks * W, 0.);
          add_contact_heat(lagged_contact_heat, &lagged_partials);
        }
      if (!use_implicit)
        {
          heat_rates(time, rate, partials);
          for (unsigned int n = 3 * first_element; n < 3 * end_element; ++n)
            if (!dirichlet_node[n])
              T[n] += time_step * rate[n] / lumped_capacity[n];
          set_dirichlet_values(time + time_step);
        }
      else
        {
          solve_implicit(time, time_step, T_old, lagged_contact_heat);
          heat_rates(time + time_step, rate, partials);
          if (lagged_contact)
            {
              // the balance with the contact heat the step used
              Vector<double> current_contact_heat(model.n_nodes);
              add_contact_heat(current_contact_heat, nullptr);
              rate -= current_contact_heat;
              rate += lagged_contact_heat;
              for (unsigned int c = 0; c < n_chunks; ++c)
                partials[c * W + 2] = lagged_partials[c * W + 2];
            }
        }
      // stored heat (lumped or consistent capacity, as the step) and the
      // Dirichlet heat from the residual of the held nodes, per chunk
      const unsigned int n_slots = balance_slot.size();
      for (unsigned int e = first_element; e < end_element; ++e)
        {
          double *sums = &partials[chunk_of(e) * W];
          for (unsigned int a = 0; a < 3; ++a)
            {
              const unsigned int n = 3 * e + a;
              double             stored_change =
                use_implicit ? 0. : lumped_capacity[n] * (T[n] - T_old[n]);
              if (use_implicit)
                for (unsigned int b = 0; b < 3; ++b)
                  stored_change +=
                    implicit_capacity<2>(lumped_implicit_capacity,
                                         volumetric_heat_capacity[e],
                                         model.reference_area[e],
                                         a,
                                         b) *
                    (T[3 * e + b] - T_old[3 * e + b]);
              sums[0] += stored_change;
              if (dirichlet_node[n])
                {
                  // which boundary id: the first of its condition
                  const unsigned int slot =
                    balance_slot.at(parameters.thermal_boundary
                                      .conditions[dirichlet_condition[n]]
                                      .boundary_ids.front());
                  sums[3 + n_slots + slot] +=
                    stored_change - time_step * rate[n];
                  sums[3 + 2 * n_slots + slot] +=
                    stored_change / time_step - rate[n];
                }
            }
        }
      std::vector<double> totals;
      reduce_chunks(partials, W, totals);
      heat_balance.stored_heat += totals[0];
      heat_balance.source_heat += time_step * totals[1];
      last_contact_exchange = totals[2];
      heat_balance.contact_exchange += time_step * totals[2];
      for (const auto &[id, slot] : balance_slot)
        {
          heat_balance.boundary_heat_in[id] +=
            time_step * totals[3 + slot] + totals[3 + n_slots + slot];
          last_rate[id] = totals[3 + slot] + totals[3 + 2 * n_slots + slot];
        }
    }

    void
    DiscreteHeat::interpolate_from_vertices(
      const std::vector<double> &vertex_values)
    {
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        T[n] = vertex_values[model.node_vertex[n]];
    }

    std::vector<double>
    DiscreteHeat::average_to_vertices() const
    {
      unsigned int n_vertices = 0;
      for (const auto v : model.node_vertex)
        n_vertices = std::max(n_vertices, v + 1);
      std::vector<double>       sum(n_vertices, 0.);
      std::vector<unsigned int> count(n_vertices, 0);
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          sum[model.node_vertex[n]] += T[n];
          ++count[model.node_vertex[n]];
        }
      for (unsigned int v = 0; v < n_vertices; ++v)
        if (count[v] > 0)
          sum[v] /= count[v];
      return sum;
    }

    void
    DiscreteHeat::save(CheckpointWriter &out) const
    {
      out.put_array(T.begin(), T.size());
      out.put(heat_balance.boundary_heat_in);
      out.put(heat_balance.source_heat);
      out.put(heat_balance.contact_heat);
      out.put(heat_balance.contact_exchange);
      out.put(heat_balance.stored_heat);
      out.put(last_rate);
      out.put(iterations);
      out.put(last_contact_exchange);
    }

    void
    DiscreteHeat::load(CheckpointReader &in)
    {
      in.get_array(T.begin(), T.size());
      in.get(heat_balance.boundary_heat_in);
      in.get(heat_balance.source_heat);
      in.get(heat_balance.contact_heat);
      in.get(heat_balance.contact_exchange);
      in.get(heat_balance.stored_heat);
      in.get(last_rate);
      in.get(iterations);
      in.get(last_contact_exchange);
    }
  } // namespace discrete
} // namespace tmfdem
