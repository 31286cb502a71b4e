#include <algorithm>
#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/heat_kernel.h>
#include <tmfdem/discrete/tetrahedral_heat.h>
#include <tmfdem/discrete/tetrahedron_contact_system.h>
#include <tmfdem/io/checkpoint.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** The current nodes of tetrahedron @p e as x[i][k] pointers. */
      struct TetrahedronNodes
      {
        TetrahedronNodes(const DiscreteModel &m, const unsigned int e)
          : x{&m.x[4 * e], &m.y[4 * e], &m.z[4 * e]}
        {}
        const double *const x[3];
      };

      /** A third of the current area of face @p f of tetrahedron @p e
       *  (deal.II's face f holds every vertex but 3 - f) [m^2], and its
       *  three nodes in @p nodes. */
      double
      face_third(const DiscreteModel &m,
                 const unsigned int   e,
                 const unsigned int   f,
                 unsigned int (&nodes)[3])
      {
        unsigned int n = 0;
        for (unsigned int k = 0; k < 4; ++k)
          if (k != 3 - f)
            nodes[n++] = 4 * e + k;
        double a[3], b[3];
        for (unsigned int i = 0; i < 3; ++i)
          {
            const std::vector<double> &c = i == 0 ? m.x : (i == 1 ? m.y : m.z);
            a[i]                         = c[nodes[1]] - c[nodes[0]];
            b[i]                         = c[nodes[2]] - c[nodes[0]];
          }
        const double cx = a[1] * b[2] - a[2] * b[1];
        const double cy = a[2] * b[0] - a[0] * b[2];
        const double cz = a[0] * b[1] - a[1] * b[0];
        return std::sqrt(cx * cx + cy * cy + cz * cz) / 6.;
      }

      Point<3>
      reference_point(const DiscreteModel &m, const unsigned int n)
      {
        return Point<3>(m.x_ref[n], m.y_ref[n], m.z_ref[n]);
      }
    } // namespace

    TetrahedralHeat::TetrahedralHeat(const Parameters &parameters,
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
      tolerance                = dh.solver_tolerance;
      contact_conductance      = dh.contact_conductance;
      contact_model            = dh.contact_heat_model;
      n_chunks = (model.n_elements + chunk_elements - 1) / chunk_elements;
      T.assign(model.n_nodes, 0.);
      conductivity.resize(model.n_elements);
      volumetric_heat_capacity.resize(model.n_elements);
      lumped_capacity.assign(model.n_nodes, 0.);
      element_matrix.assign(16 * model.n_elements, 0.);
      sources.resize(256);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const types::material_id  id = model.material[e];
          const MaterialProperties &m  = parameters.materials[id];
          if (m.anisotropic_conductivity)
            throw InputError(
              "Materials/Material " + std::to_string(id) +
              "/Thermal conductivity along, across: anisotropic conduction "
              "(a direction in the plane) is 2D only; allowed with "
              "Mesh/Dimension = 3 is an isotropic Thermal conductivity.");
          conductivity[e]             = m.thermal_conductivity;
          volumetric_heat_capacity[e] = m.density * m.specific_heat;
          for (unsigned int k = 0; k < 4; ++k)
            lumped_capacity[4 * e + k] =
              volumetric_heat_capacity[e] * model.reference_area[e] / 4.;
          if (!sources[id] && m.heat_source != "0")
            sources[id] =
              make_expression_function<3>(m.heat_source,
                                          "Materials/Material " +
                                            std::to_string(id) +
                                            "/Volumetric heat source");
        }

      // each node's joint partners: a node lies on three faces of its
      // tetrahedron; every intact face joint pairs it with the node of
      // the same vertex on the other side
      partner.assign(3 * model.n_nodes, -1);
      partner_joint.assign(3 * model.n_nodes, -1);
      partner_conductance.assign(3 * model.n_nodes, 0.);
      std::vector<unsigned char> slots(model.n_nodes, 0);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int f = 0; f < 4; ++f)
          {
            const int code = model.edge_joint[4 * e + f];
            if (code < 0)
              continue;
            const unsigned int  j    = code / 2;
            const unsigned int  side = code % 2;
            const unsigned int *p    = &model.joint_nodes[6 * j];
            const double        ka = conductivity[model.joint_elements[2 * j]];
            const double kb = conductivity[model.joint_elements[2 * j + 1]];
            const double G  = joint_pair_conductance<3>(beta,
                                                       2. * ka * kb / (ka + kb),
                                                       model.joint_area[j],
                                                       model.joint_length[j]);
            for (unsigned int k = 0; k < 3; ++k)
              {
                const unsigned int node = p[3 * side + k];
                const unsigned int s    = 3 * node + slots[node]++;
                partner[s]              = p[3 * (1 - side) + k];
                partner_joint[s]        = j;
                partner_conductance[s]  = G;
              }
          }

      // boundary conditions on the faces with their ids
      std::vector<int> condition_of_id(256, -1);
      for (const auto &c : parameters.thermal_boundary.conditions)
        {
          ConditionFunctions f;
          f.type = c.type;
          f.temperature =
            make_expression_function<3>(c.temperature, c.name + "/Temperature");
          f.flux =
            make_expression_function<3>(c.heat_flux, c.name + "/Heat flux");
          f.coefficient =
            make_expression_function<3>(c.heat_transfer_coefficient,
                                        c.name + "/Heat transfer coefficient");
          f.ambient =
            make_expression_function<3>(c.ambient_temperature,
                                        c.name + "/Ambient temperature");
          model.check_boundary_ids(c.name + "/Boundary ids", c.boundary_ids);
          for (const auto id : c.boundary_ids)
            condition_of_id[id] = conditions.size();
          conditions.push_back(std::move(f));
        }
      dirichlet_node.assign(model.n_nodes, 0);
      dirichlet_condition.assign(model.n_nodes, 0);
      std::map<unsigned int, unsigned int> dirichlet_vertex;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int f = 0; f < 4; ++f)
          {
            const types::boundary_id id = model.edge_boundary[4 * e + f];
            if (id == numbers::internal_face_boundary_id)
              continue;
            heat_balance.boundary_heat_in[id] += 0.;
            if (condition_of_id[id] < 0)
              continue;
            const unsigned int c = condition_of_id[id];
            boundary_faces.push_back({e, f, c, id});
            if (conditions[c].type == ThermalBoundaryCondition::Type::dirichlet)
              for (unsigned int k = 0; k < 4; ++k)
                if (k != 3 - f)
                  dirichlet_vertex[model.node_vertex[4 * e + k]] = c;
          }
      // every node on a held vertex is held, not only those of the
      // tetrahedra that own the boundary face
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          const auto it = dirichlet_vertex.find(model.node_vertex[n]);
          if (it != dirichlet_vertex.end())
            {
              dirichlet_node[n]      = 1;
              dirichlet_condition[n] = it->second;
            }
        }
      for (const auto &[id, heat] : heat_balance.boundary_heat_in)
        {
          const unsigned int slot = balance_slot.size();
          balance_slot[id]        = slot;
        }
      robin_diagonal.assign(model.n_nodes, 0.);
    }

    void
    TetrahedralHeat::set_function_time(const double time) const
    {
      for (const auto &c : conditions)
        {
          c.temperature->set_time(time);
          c.flux->set_time(time);
          c.coefficient->set_time(time);
          c.ambient->set_time(time);
        }
      for (const auto &s : sources)
        if (s)
          s->set_time(time);
    }

    void
    TetrahedralHeat::initialise(const double time)
    {
      std::map<types::material_id, std::unique_ptr<FunctionParser<3>>>
        initial_of;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          auto &f = initial_of[model.material[e]];
          if (!f)
            {
              const InitialTemperatureEntry entry =
                parameters.initial_temperature_of(model.material[e]);
              f = make_expression_function<3>(entry.expression, entry.entry);
              f->set_time(time);
            }
          for (unsigned int n = 4 * e; n < 4 * e + 4; ++n)
            T[n] = f->value(reference_point(model, n));
        }
      set_function_time(time);
      update_contact_pairs(); // the heat alone: its own search, once
    }

    void
    TetrahedralHeat::set_dirichlet_values(const double time)
    {
      set_function_time(time);
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        if (dirichlet_node[n])
          T[n] = conditions[dirichlet_condition[n]].temperature->value(
            reference_point(model, n));
    }

    double
    TetrahedralHeat::nodal_source(const unsigned int e) const
    {
      const auto &source = sources[model.material[e]];
      if (!source)
        return 0.;
      Point<3> centroid;
      for (unsigned int n = 4 * e; n < 4 * e + 4; ++n)
        centroid += 0.25 * reference_point(model, n);
      return source->value(centroid) * model.reference_area[e] / 4.;
    }

    template <typename Function>
    double
    TetrahedralHeat::chunked_sum(const Function &f) const
    {
      std::vector<double> sums(n_chunks, 0.);
      for_each_chunk(arena_for(n_threads),
                     model.n_elements,
                     chunk_elements,
                     [&](const std::size_t begin,
                         const std::size_t end,
                         const std::size_t c) { sums[c] = f(begin, end); });
      double total = 0.;
      for (const double s : sums)
        total += s;
      return total;
    }

    template <typename Function>
    void
    TetrahedralHeat::for_each_flux_node(const Function &f) const
    {
      for (const BoundaryFace &b : boundary_faces)
        {
          if (conditions[b.condition].type ==
              ThermalBoundaryCondition::Type::dirichlet)
            continue;
          unsigned int nodes[3];
          const double third = face_third(model, b.element, b.face, nodes);
          for (const unsigned int n : nodes)
            f(b, n, third);
        }
    }

    void
    TetrahedralHeat::update_element_matrices()
    {
      for_each_chunk(
        arena_for(n_threads),
        model.n_elements,
        chunk_elements,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t e = begin; e < end; ++e)
            {
              const TetrahedronNodes nodes(model, e);
              double                 K[4][4];
              conductivity_matrix<3, double>(nodes.x, conductivity[e], K);
              if (conduction_m_matrix)
                make_conduction_m_matrix(K);
              std::copy(&K[0][0], &K[0][0] + 16, &element_matrix[16 * e]);
            }
        });
    }

    double
    TetrahedralHeat::stable_time_step() const
    {
      // Gershgorin: lambda_max <= max_n (sum_b |K_nb| + 2 sum G + h A/3 +
      // contact) / C_n over the free nodes; all but the contact at the
      // reference geometry, once
      if (row_bound.empty())
        {
          row_bound.assign(model.n_nodes, 0.);
          set_function_time(0.);
          for_each_flux_node([&](const BoundaryFace &b,
                                 const unsigned int  n,
                                 const double        third) {
            if (conditions[b.condition].type ==
                ThermalBoundaryCondition::Type::robin)
              row_bound[n] +=
                third * conditions[b.condition].coefficient->value(
                          reference_point(model, n));
          });
          for (unsigned int e = 0; e < model.n_elements; ++e)
            {
              double              X[3][4];
              const double *const x[3] = {X[0], X[1], X[2]};
              for (unsigned int k = 0; k < 4; ++k)
                {
                  X[0][k] = model.x_ref[4 * e + k];
                  X[1][k] = model.y_ref[4 * e + k];
                  X[2][k] = model.z_ref[4 * e + k];
                }
              double K[4][4];
              conductivity_matrix<3, double>(x, conductivity[e], K);
              if (conduction_m_matrix)
                make_conduction_m_matrix(K);
              for (unsigned int a = 0; a < 4; ++a)
                {
                  const unsigned int n = 4 * e + a;
                  for (unsigned int b = 0; b < 4; ++b)
                    row_bound[n] += std::abs(K[a][b]);
                  for (unsigned int s = 3 * n; s < 3 * n + 3; ++s)
                    row_bound[n] += 2. * partner_conductance[s];
                }
            }
        }
      // contact: K = h_c A w w^T has the row sums 2 h_c A N_k; the paper
      // literal term s_i dQ/dT_j, s = (N_c, -N_t), N_k sum |dQ/dT|
      std::vector<double> contact_row;
      if (!contact_pairs.empty())
        {
          contact_row.assign(model.n_nodes, 0.);
          const double zero[4] = {0., 0., 0., 0.};
          for (const HeatContactPair &pair : contact_pairs)
            {
              TetrahedronContactHeat transfer;
              tetrahedron_contact_heat(contact_model,
                                       pair.interface,
                                       zero,
                                       zero,
                                       contact_conductance,
                                       transfer);
              double weights = 2. * transfer.conductance;
              for (const double w : transfer.flow_weights)
                weights += std::abs(w);
              for (unsigned int k = 0; k < 4; ++k)
                {
                  contact_row[4 * pair.first + k] +=
                    transfer.contactor_shape[k] * weights;
                  contact_row[4 * pair.second + k] +=
                    transfer.target_shape[k] * weights;
                }
            }
        }
      double lambda = 0.;
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        if (!dirichlet_node[n])
          lambda = std::max(lambda,
                            (row_bound[n] +
                             (contact_row.empty() ? 0. : contact_row[n])) /
                              lumped_capacity[n]);
      return lambda > 0. ? 2. / lambda : 1e300;
    }

    void
    TetrahedralHeat::update_contact_pairs()
    {
      if (!(contact_conductance > 0.))
        return;
      if (shared_pairs == nullptr && own_pairs_found)
        return; // the heat alone: the geometry does not change
      std::vector<TetrahedronContactPair>        own;
      const std::vector<TetrahedronContactPair> *candidates = shared_pairs;
      if (candidates == nullptr)
        {
          // tetrahedra with a free face and their intact neighbours; boxes
          // that overlap (no buffer); pairs joined by an intact joint
          // excluded
          std::vector<unsigned int> elements;
          model.contact_candidate_elements(elements);
          LinkedCellSearchT<3, TetrahedronContactPair> search;
          const std::vector<double> *const coordinates[3] = {&model.x,
                                                             &model.y,
                                                             &model.z};
          search.rebuild(
            coordinates,
            elements,
            0.,
            [&](const unsigned int a, const unsigned int b) {
              return model.joined(a, b);
            },
            own,
            arena_for(n_threads));
          candidates      = &own;
          own_pairs_found = true;
        }
      const bool literal = contact_model == ContactHeatModel::paper_literal;
      std::vector<HeatContactPair> found(candidates->size());
      std::vector<char>            touching(candidates->size(), 0);
      for_each_chunk(
        arena_for(n_threads),
        candidates->size(),
        256,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t p = begin; p < end; ++p)
            {
              const unsigned int e[2] = {(*candidates)[p].first,
                                         (*candidates)[p].second};
              double             x[2][4][3];
              // bit f: the face opposite node f (deal.II's face 3 - f) is
              // free, a boundary face or a broken joint's
              unsigned char free_faces[2] = {0, 0};
              for (unsigned int side = 0; side < 2; ++side)
                for (unsigned int k = 0; k < 4; ++k)
                  {
                    const unsigned int node = 4 * e[side] + k;
                    x[side][k][0]           = model.x[node];
                    x[side][k][1]           = model.y[node];
                    x[side][k][2]           = model.z[node];
                    if (model.intact_neighbour(e[side], 3 - k) < 0)
                      free_faces[side] |= 1 << k;
                  }
              found[p].first  = e[0];
              found[p].second = e[1];
              touching[p]     = tetrahedron_contact_interface(x,
                                                          free_faces,
                                                          literal,
                                                          found[p].interface);
            }
        });
      contact_pairs.clear();
      for (std::size_t p = 0; p < found.size(); ++p)
        if (touching[p])
          contact_pairs.push_back(found[p]);
    }

    double
    TetrahedralHeat::add_contact_heat(const std::vector<double> &temperatures,
                                      std::vector<double>       &rate) const
    {
      double exchange = 0.;
      for (const HeatContactPair &pair : contact_pairs)
        {
          TetrahedronContactHeat transfer;
          tetrahedron_contact_heat(contact_model,
                                   pair.interface,
                                   &temperatures[4 * pair.first],
                                   &temperatures[4 * pair.second],
                                   contact_conductance,
                                   transfer);
          for (unsigned int k = 0; k < 4; ++k)
            {
              rate[4 * pair.first + k] += transfer.contactor_nodal_heat[k];
              rate[4 * pair.second + k] += transfer.target_nodal_heat[k];
            }
          exchange += std::abs(transfer.heat_flow);
        }
      return exchange;
    }

    void
    TetrahedralHeat::heat_rates(const double         time,
                                std::vector<double> &rate,
                                std::vector<double> &partials)
    {
      const unsigned int W = 2 + 3 * balance_slot.size();
      // conduction and joints, per tetrahedron (each writes its own nodes)
      for_each_row(T, [&](const std::size_t n, const double product) {
        rate[n] = -product;
      });
      set_function_time(time);
      // sources at the centroid, lumped a quarter per node
      for (unsigned int e = 0; e < model.n_elements; ++e)
        if (const double q = nodal_source(e); q != 0.)
          {
            for (unsigned int n = 4 * e; n < 4 * e + 4; ++n)
              rate[n] += q;
            partials[(e / chunk_elements) * W + 1] += 4. * q;
          }
      // Neumann and Robin
      for_each_flux_node(
        [&](const BoundaryFace &b, const unsigned int n, const double third) {
          const ConditionFunctions &f = conditions[b.condition];
          const Point<3>            p = reference_point(model, n);
          const double              q =
            f.type == ThermalBoundaryCondition::Type::neumann ?
                           third * f.flux->value(p) :
                           third * f.coefficient->value(p) * (f.ambient->value(p) - T[n]);
          rate[n] += q;
          partials[(b.element / chunk_elements) * W + 2 +
                   balance_slot.at(b.id)] += q;
        });
    }

    template <typename Row>
    void
    TetrahedralHeat::for_each_row(const std::vector<double> &x,
                                  const Row                 &row) const
    {
      for_each_chunk(
        arena_for(n_threads),
        model.n_elements,
        chunk_elements,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t e = begin; e < end; ++e)
            {
              const double *A = &element_matrix[16 * e];
              for (unsigned int a = 0; a < 4; ++a)
                {
                  const std::size_t n   = 4 * e + a;
                  double            sum = 0.;
                  for (unsigned int b = 0; b < 4; ++b)
                    sum += A[4 * a + b] * x[4 * e + b];
                  for (std::size_t s = 3 * n; s < 3 * n + 3; ++s)
                    if (partner[s] >= 0 &&
                        model.joint_status[partner_joint[s]] ==
                          JointStatus::intact)
                      sum += partner_conductance[s] * (x[n] - x[partner[s]]);
                  row(n, sum);
                }
            }
        });
    }

    void
    TetrahedralHeat::apply(const std::vector<double> &x,
                           std::vector<double>       &y) const
    {
      for_each_row(x, [&](const std::size_t n, const double product) {
        y[n] = dirichlet_node[n] ? 0. : product + robin_diagonal[n] * x[n];
      });
      if (!contact_in_matrix())
        return;
      // + h_c A w w^T x, w = (N_c, -N_t), in pair order
      for (const HeatContactPair &pair : contact_pairs)
        {
          const auto  &N = pair.interface.shape;
          const double s =
            contact_conductance * pair.interface.area *
            (N[0][0] * x[4 * pair.first] + N[0][1] * x[4 * pair.first + 1] +
             N[0][2] * x[4 * pair.first + 2] + N[0][3] * x[4 * pair.first + 3] -
             N[1][0] * x[4 * pair.second] - N[1][1] * x[4 * pair.second + 1] -
             N[1][2] * x[4 * pair.second + 2] -
             N[1][3] * x[4 * pair.second + 3]);
          for (unsigned int k = 0; k < 4; ++k)
            {
              const unsigned int a = 4 * pair.first + k,
                                 b = 4 * pair.second + k;
              if (!dirichlet_node[a])
                y[a] += N[0][k] * s;
              if (!dirichlet_node[b])
                y[b] -= N[1][k] * s;
            }
        }
    }

    void
    TetrahedralHeat::solve_implicit(
      const double               time,
      const double               time_step,
      const std::vector<double> &T_old,
      const std::vector<double> &lagged_contact_heat)
    {
      const unsigned int N = model.n_nodes;
      // the step's matrix per tetrahedron: K + M / dt
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int b = 0; b < 4; ++b)
            element_matrix[16 * e + 4 * a + b] +=
              implicit_capacity<3>(lumped_implicit_capacity,
                                   volumetric_heat_capacity[e],
                                   model.reference_area[e],
                                   a,
                                   b) /
              time_step;
      // right-hand side at t + dt: M/dt T_old, sources, Neumann, Robin's
      // ambient part (its T part on the diagonal)
      std::vector<double> rhs(N, 0.);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int a = 0; a < 4; ++a)
          {
            double capacity_T = 0.;
            for (unsigned int b = 0; b < 4; ++b)
              capacity_T += implicit_capacity<3>(lumped_implicit_capacity,
                                                 volumetric_heat_capacity[e],
                                                 model.reference_area[e],
                                                 a,
                                                 b) *
                            T_old[4 * e + b];
            rhs[4 * e + a] = capacity_T / time_step;
          }
      set_function_time(time + time_step);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        if (const double q = nodal_source(e); q != 0.)
          for (unsigned int n = 4 * e; n < 4 * e + 4; ++n)
            rhs[n] += q;
      // the paper literal contact heat, at the old temperatures
      for (unsigned int n = 0; n < lagged_contact_heat.size(); ++n)
        rhs[n] += lagged_contact_heat[n];
      std::fill(robin_diagonal.begin(), robin_diagonal.end(), 0.);
      for_each_flux_node(
        [&](const BoundaryFace &b, const unsigned int n, const double third) {
          const ConditionFunctions &f = conditions[b.condition];
          const Point<3>            p = reference_point(model, n);
          if (f.type == ThermalBoundaryCondition::Type::neumann)
            rhs[n] += third * f.flux->value(p);
          else
            {
              const double h = third * f.coefficient->value(p);
              robin_diagonal[n] += h;
              rhs[n] += h * f.ambient->value(p);
            }
        });
      // T holds T_old; the held nodes take their values at t + dt
      set_dirichlet_values(time + time_step);

      // conjugate gradients with the diagonal, on the free nodes
      std::vector<double> r(N), z(N), p(N), q(N), diagonal(N, 1.);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int a = 0; a < 4; ++a)
          {
            const unsigned int n = 4 * e + a;
            double d = element_matrix[16 * e + 5 * a] + robin_diagonal[n];
            for (unsigned int s = 3 * n; s < 3 * n + 3; ++s)
              if (partner[s] >= 0 &&
                  model.joint_status[partner_joint[s]] == JointStatus::intact)
                d += partner_conductance[s];
            diagonal[n] = d;
          }
      if (contact_in_matrix())
        for (const HeatContactPair &pair : contact_pairs)
          for (unsigned int side = 0; side < 2; ++side)
            for (unsigned int k = 0; k < 4; ++k)
              {
                const double N = pair.interface.shape[side][k];
                diagonal[4 * (side == 0 ? pair.first : pair.second) + k] +=
                  contact_conductance * pair.interface.area * N * N;
              }
      apply(T, q);
      for (unsigned int n = 0; n < N; ++n)
        {
          r[n] = dirichlet_node[n] ? 0. : rhs[n] - q[n];
          z[n] = r[n] / diagonal[n];
          p[n] = z[n];
        }
      const auto dot = [&](const std::vector<double> &u,
                           const std::vector<double> &v) {
        return chunked_sum([&](const std::size_t begin, const std::size_t end) {
          double s = 0.;
          for (std::size_t n = 4 * begin; n < 4 * end; ++n)
            s += u[n] * v[n];
          return s;
        });
      };
      for (unsigned int n = 0; n < N; ++n)
        if (dirichlet_node[n])
          rhs[n] = 0.;
      // relative to the larger of the right-hand side and the first
      // residual (which holds the Dirichlet values' pull)
      const double target =
        tolerance * std::sqrt(std::max(dot(rhs, rhs), dot(r, r)));
      double             rz             = dot(r, z);
      const unsigned int max_iterations = 10000;
      iterations                        = 0;
      while (rz > 0. && std::sqrt(dot(r, r)) > target)
        {
          if (iterations == max_iterations)
            throw RunError(
              "discrete heat (3D), step at t = " + Utilities::to_string(time) +
              " s: the conjugate gradients did not reach Discrete heat/Linear "
              "solver tolerance = " +
              Utilities::to_string(tolerance) + " in " +
              std::to_string(max_iterations) +
              " iterations; allowed: a larger tolerance or a shorter step.");
          apply(p, q);
          const double alpha = rz / dot(p, q);
          for (unsigned int n = 0; n < N; ++n)
            {
              T[n] += alpha * p[n];
              r[n] -= alpha * q[n];
              z[n] = r[n] / diagonal[n];
            }
          const double rz_new = dot(r, z);
          const double beta_k = rz_new / rz;
          rz                  = rz_new;
          for (unsigned int n = 0; n < N; ++n)
            p[n] = z[n] + beta_k * p[n];
          ++iterations;
        }
    }

    void
    TetrahedralHeat::step(const double time, const double time_step)
    {
      const std::vector<double> T_old   = T;
      const unsigned int        n_slots = balance_slot.size();
      const unsigned int        W       = 2 + 3 * n_slots;
      std::vector<double>       partials(n_chunks * W, 0.);
      std::vector<double>       rate(model.n_nodes, 0.);
      update_element_matrices();
      update_contact_pairs();
      double exchange = 0.; // sum of |Q| of the contact pairs [W]
      if (!use_implicit)
        {
          if (!contact_pairs.empty() && time_step > stable_time_step())
            throw RunError(
              "discrete heat (3D), step at t = " + Utilities::to_string(time) +
              " s: the thermal step " + Utilities::to_string(time_step) +
              " s exceeds the stable explicit step " +
              Utilities::to_string(stable_time_step()) +
              " s with the contact heat of the " +
              std::to_string(contact_pairs.size()) +
              " pairs in contact now (Discrete heat/Contact conductance = " +
              Utilities::to_string(contact_conductance) +
              " W/(m^2 K)); allowed: Discrete heat/Time integration = "
              "implicit, a smaller Contact conductance or a shorter thermal "
              "step.");
          heat_rates(time, rate, partials);
          exchange = add_contact_heat(T, rate);
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            if (!dirichlet_node[n])
              T[n] += time_step * rate[n] / lumped_capacity[n];
          set_dirichlet_values(time + time_step);
        }
      else
        {
          // the paper literal contact heat is not a conductance: explicit
          // (lagged) in the backward Euler step, as in 2D
          std::vector<double> lagged;
          double              lagged_exchange = 0.;
          if (!contact_pairs.empty() && !contact_in_matrix())
            {
              lagged.assign(model.n_nodes, 0.);
              lagged_exchange = add_contact_heat(T_old, lagged);
            }
          solve_implicit(time, time_step, T_old, lagged);
          // the rates at the new temperatures (what backward Euler used),
          // with the conductivity matrices alone again (the solve added M/dt)
          update_element_matrices();
          heat_rates(time + time_step, rate, partials);
          if (!lagged.empty())
            {
              for (unsigned int n = 0; n < model.n_nodes; ++n)
                rate[n] += lagged[n];
              exchange = lagged_exchange;
            }
          else
            exchange = add_contact_heat(T, rate);
        }
      heat_balance.contact_exchange += time_step * exchange;
      // stored heat (lumped or consistent capacity, as the step) and the
      // heat of the held nodes from their residual, per chunk
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          double *sums = &partials[(e / chunk_elements) * W];
          for (unsigned int a = 0; a < 4; ++a)
            {
              const unsigned int n = 4 * e + a;
              double             stored_change =
                use_implicit ? 0. : lumped_capacity[n] * (T[n] - T_old[n]);
              if (use_implicit)
                for (unsigned int b = 0; b < 4; ++b)
                  stored_change +=
                    implicit_capacity<3>(lumped_implicit_capacity,
                                         volumetric_heat_capacity[e],
                                         model.reference_area[e],
                                         a,
                                         b) *
                    (T[4 * e + b] - T_old[4 * e + b]);
              sums[0] += stored_change;
              if (dirichlet_node[n])
                {
                  const unsigned int slot =
                    balance_slot.at(parameters.thermal_boundary
                                      .conditions[dirichlet_condition[n]]
                                      .boundary_ids.front());
                  sums[2 + n_slots + slot] +=
                    stored_change - time_step * rate[n];
                  sums[2 + 2 * n_slots + slot] +=
                    stored_change / time_step - rate[n];
                }
            }
        }
      std::vector<double> totals(W, 0.);
      for (unsigned int c = 0; c < n_chunks; ++c)
        for (unsigned int i = 0; i < W; ++i)
          totals[i] += partials[c * W + i];
      heat_balance.stored_heat += totals[0];
      heat_balance.source_heat += time_step * totals[1];
      for (const auto &[id, slot] : balance_slot)
        {
          heat_balance.boundary_heat_in[id] +=
            time_step * totals[2 + slot] + totals[2 + n_slots + slot];
          last_rate[id] = totals[2 + slot] + totals[2 + 2 * n_slots + slot];
        }
    }

    void
    TetrahedralHeat::save(CheckpointWriter &out) const
    {
      out.put(T);
      out.put(heat_balance.boundary_heat_in);
      out.put(heat_balance.source_heat);
      out.put(heat_balance.stored_heat);
      out.put(heat_balance.contact_exchange);
      out.put(last_rate);
      out.put(iterations);
    }

    void
    TetrahedralHeat::load(CheckpointReader &in)
    {
      in.get(T, model.n_nodes);
      in.get(heat_balance.boundary_heat_in);
      in.get(heat_balance.source_heat);
      in.get(heat_balance.stored_heat);
      in.get(heat_balance.contact_exchange);
      in.get(last_rate);
      in.get(iterations);
    }
  } // namespace discrete
} // namespace tmfdem
