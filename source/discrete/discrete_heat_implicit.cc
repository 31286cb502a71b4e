/**
 * @file
 * The implicit (backward Euler) step of the discrete layer's own heat
 * (DiscreteHeat, paper Eq. 22): each rank assembles the rows of its own
 * nodes (consistent capacity M/dt + conduction K, joint exchange, contact
 * conductance, Robin) into a NodeRowSystem, eliminates the Dirichlet
 * values from rows and columns, and solves with its reproducible conjugate
 * gradients: the temperatures are bitwise the same on any number of ranks
 * and threads (with the Jacobi preconditioner).
 */
#include <algorithm>
#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_heat.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/heat_kernel.h>
#include <tmfdem/discrete/partition.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    DiscreteHeat::make_row_pattern()
    {
      const unsigned int first_row = 3 * first_element;
      const unsigned int n_rows    = 3 * (end_element - first_element);
      std::vector<std::vector<unsigned int>> columns(n_rows);
      const auto couple = [&](const unsigned int i, const unsigned int j) {
        if (owns_node(i))
          columns[i - first_row].push_back(j);
      };
      for (unsigned int e = first_element; e < end_element; ++e)
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            couple(3 * e + a, 3 * e + b);
      // every joint here, broken or not: the pattern holds until the
      // contact pairs change
      for (const unsigned int j : local_joints)
        for (unsigned int end = 0; end < 2; ++end)
          {
            const unsigned int a = model.joint_nodes[4 * j + end];
            const unsigned int b = model.joint_nodes[4 * j + 2 + end];
            couple(a, b);
            couple(b, a);
          }
      for (const auto &[c, t] : contact_pairs)
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            {
              couple(3 * c + a, 3 * t + b);
              couple(3 * t + b, 3 * c + a);
            }
      rows.set_pattern(columns);
    }

    void
    DiscreteHeat::solve_implicit(const double          time,
                                 const double          time_step,
                                 const Vector<double> &T_old,
                                 const Vector<double> &lagged_contact_heat)
    {
      NodeRowSystem::Layout layout;
      layout.n_nodes        = model.n_nodes;
      layout.first_element  = first_element;
      layout.end_element    = end_element;
      layout.chunk_elements = chunk_elements;
      layout.n_chunks       = n_chunks;
      layout.n_threads      = n_threads;
      layout.partition      = partition;
      rows.set_layout(layout);
      if (!rows.has_pattern())
        make_row_pattern();
      const unsigned int first_row = 3 * first_element;
      const unsigned int last_row  = 3 * end_element;
      set_function_time(time + time_step);

      // matrix: M/dt + K, joints, contact conductance, Robin
      rows.zero_values();
      for (unsigned int e = first_element; e < end_element; ++e)
        {
          double K[3][3];
          element_conductivity_matrix(e, K);
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int b = 0; b < 3; ++b)
              rows.add(3 * e + a,
                       3 * e + b,
                       K[a][b] +
                         implicit_capacity<2>(lumped_implicit_capacity,
                                              volumetric_heat_capacity[e],
                                              model.reference_area[e],
                                              a,
                                              b) /
                           time_step);
        }
      for (const unsigned int j : local_joints)
        if (model.joint_status[j] == JointStatus::intact)
          for (unsigned int end = 0; end < 2; ++end)
            {
              const unsigned int a = model.joint_nodes[4 * j + end];
              const unsigned int b = model.joint_nodes[4 * j + 2 + end];
              const double       G = joint_conductance[j];
              rows.add(a, a, G);
              rows.add(b, b, G);
              rows.add(a, b, -G);
              rows.add(b, a, -G);
            }
      // contact conductance: +K = h_c L_c w w^T, w = (N_c, -N_t)
      for_each_contact_transfer([&](const unsigned int         c,
                                    const unsigned int         t,
                                    const ContactHeatTransfer &transfer) {
        const auto         J = transfer.heat_jacobian();
        const unsigned int nodes[6] =
          {3 * c, 3 * c + 1, 3 * c + 2, 3 * t, 3 * t + 1, 3 * t + 2};
        for (unsigned int a = 0; a < 6; ++a)
          for (unsigned int b = 0; b < 6; ++b)
            rows.add(nodes[a], nodes[b], -J[a][b]);
      });

      // right-hand side: M/dt T_old + loads at t + dt (T-independent
      // parts; Robin's T part in the matrix) + the lagged contact heat
      std::vector<double> rhs(model.n_nodes, 0.);
      for (unsigned int e = first_element; e < end_element; ++e)
        {
          for (unsigned int a = 0; a < 3; ++a)
            {
              double capacity_T = 0.;
              for (unsigned int b = 0; b < 3; ++b)
                capacity_T += implicit_capacity<2>(lumped_implicit_capacity,
                                                   volumetric_heat_capacity[e],
                                                   model.reference_area[e],
                                                   a,
                                                   b) *
                              T_old[3 * e + b];
              rhs[3 * e + a] += capacity_T / time_step;
            }
          const double *x = &model.x_ref[3 * e], *y = &model.y_ref[3 * e];
          const double  s = sources[model.material[e]]->value(
            Point<2>((x[0] + x[1] + x[2]) / 3., (y[0] + y[1] + y[2]) / 3.));
          for (unsigned int a = 0; a < 3; ++a)
            rhs[3 * e + a] += s * model.reference_area[e] / 3.;
        }
      for_each_boundary_node(
        flux_condition,
        [&](const BoundaryEdge &b, const unsigned int n, const double half) {
          const auto    &f = conditions[b.condition];
          const Point<2> p(model.x_ref[n], model.y_ref[n]);
          if (f.type == ThermalBoundaryCondition::Type::neumann)
            rhs[n] += half * f.flux->value(p);
          else
            {
              const double h = half * f.coefficient->value(p);
              rhs[n] += h * f.ambient->value(p);
              rows.add(n, n, h);
            }
        });
      if (lagged_contact_heat.size() > 0)
        for (unsigned int n = first_row; n < last_row; ++n)
          rhs[n] += lagged_contact_heat[n];

      // Dirichlet values at t + dt out of rows and columns (the matrix
      // stays symmetric); a column's value is known on every rank (the
      // condition at the node's reference position)
      std::vector<double> x(T_old.begin(), T_old.end());
      rows.impose_held_values(
        dirichlet_node,
        [&](const unsigned int n) {
          return conditions[dirichlet_condition[n]].temperature->value(
            Point<2>(model.x_ref[n], model.y_ref[n]));
        },
        x,
        rhs);

      // conjugate gradients from T_old with the held values; the ghosts of
      // x are T_old's (current: step())
      const auto &heat_parameters = parameters.get<DiscreteHeatParameters>();
      iterations                  = rows.solve(
        rhs,
        x,
        heat_parameters.solver_tolerance,
        heat_parameters.preconditioner ==
            DiscreteHeatParameters::Preconditioner::amg ?
                           NodeRowSystem::Preconditioner::amg :
                           NodeRowSystem::Preconditioner::jacobi,
        {"discrete heat",
                          "Likely causes: a boundary, source or initial temperature function "
                                           "that is not finite somewhere (e.g. an expression outside its "
                                           "domain), or a material property that is not. The outputs up to "
                                           "the last output time are intact.",
                          "Discrete heat/Linear solver tolerance"},
        time + time_step);
      for (unsigned int n = first_row; n < last_row; ++n)
        T[n] = x[n];
      if (partition != nullptr)
        partition->exchange_ghost_node_values(T.begin());
    }

  } // namespace discrete
} // namespace tmfdem
