/**
 * @file
 * The implicit (backward Euler) step of the discrete layer's own heat
 * (DiscreteHeat, paper Eq. 22): each rank assembles the rows of its own
 * nodes (consistent capacity M/dt + conduction K, joint exchange, contact
 * conductance, Robin), eliminates the Dirichlet values from rows and
 * columns, and solves with conjugate gradients and a Jacobi
 * preconditioner. Every dot product is summed per chunk of triangles and
 * the chunks added in order (DiscreteHeat::reduce_chunks()), and a row's
 * product adds its entries in column order: the iterates, and so the
 * temperatures, are bitwise the same on any number of ranks and threads.
 */
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_heat.h>
#include <tmfdem/discrete/discrete_parameters.h>
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
      row_start.assign(n_rows + 1, 0);
      row_column.clear();
      for (unsigned int i = 0; i < n_rows; ++i)
        {
          auto &list = columns[i];
          std::sort(list.begin(), list.end());
          list.erase(std::unique(list.begin(), list.end()), list.end());
          row_column.insert(row_column.end(), list.begin(), list.end());
          row_start[i + 1] = row_column.size();
        }
      row_value.assign(row_column.size(), 0.);
    }

    void
    DiscreteHeat::add_to_matrix(const unsigned int i,
                                const unsigned int j,
                                const double       v)
    {
      if (!owns_node(i))
        return;
      const unsigned int row   = i - 3 * first_element;
      const auto         begin = row_column.begin() + row_start[row];
      const auto         end   = row_column.begin() + row_start[row + 1];
      const auto         it    = std::lower_bound(begin, end, j);
      Assert(it != end && *it == j, ExcInternalError());
      row_value[it - row_column.begin()] += v;
    }

    void
    DiscreteHeat::multiply(const std::vector<double> &x,
                           std::vector<double>       &y) const
    {
      const unsigned int first_row = 3 * first_element;
      for_each_chunk(
        arena_for(n_threads),
        row_start.size() - 1,
        3 * chunk_elements,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t i = begin; i < end; ++i)
            {
              double sum = 0.;
              for (std::size_t k = row_start[i]; k < row_start[i + 1]; ++k)
                sum += row_value[k] * x[row_column[k]];
              y[first_row + i] = sum;
            }
        });
    }

    void
    DiscreteHeat::dot_products(
      const std::vector<std::pair<const double *, const double *>> &vectors,
      std::vector<double> &results) const
    {
      const unsigned int  width     = vectors.size();
      const unsigned int  first_row = 3 * first_element;
      const unsigned int  rows      = 3 * chunk_elements;
      const unsigned int  offset    = chunk_of(first_element);
      std::vector<double> partials(n_chunks * width, 0.);
      for_each_chunk(arena_for(n_threads),
                     3 * (end_element - first_element),
                     rows,
                     [&](const std::size_t begin,
                         const std::size_t end,
                         const std::size_t chunk) {
                       double *sums = &partials[(offset + chunk) * width];
                       for (unsigned int v = 0; v < width; ++v)
                         {
                           const double *a = vectors[v].first + first_row;
                           const double *b = vectors[v].second + first_row;
                           double        s = 0.;
                           for (std::size_t i = begin; i < end; ++i)
                             s += a[i] * b[i];
                           sums[v] = s;
                         }
                     });
      reduce_chunks(partials, width, results);
    }

    void
    DiscreteHeat::solve_implicit(const double          time,
                                 const double          time_step,
                                 const Vector<double> &T_old,
                                 const Vector<double> &lagged_contact_heat)
    {
      if (row_start.empty())
        make_row_pattern();
      const unsigned int first_row = 3 * first_element;
      const unsigned int last_row  = 3 * end_element;
      set_function_time(time + time_step);

      // matrix: M/dt + K, joints, contact conductance, Robin
      std::fill(row_value.begin(), row_value.end(), 0.);
      for (unsigned int e = first_element; e < end_element; ++e)
        {
          double K[3][3];
          element_conductivity_matrix(e, K);
          const double c =
            volumetric_heat_capacity[e] * model.reference_area[e] / 12.;
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int b = 0; b < 3; ++b)
              add_to_matrix(3 * e + a,
                            3 * e + b,
                            K[a][b] + c * (a == b ? 2. : 1.) / time_step);
        }
      for (const unsigned int j : local_joints)
        if (model.joint_status[j] == JointStatus::intact)
          for (unsigned int end = 0; end < 2; ++end)
            {
              const unsigned int a = model.joint_nodes[4 * j + end];
              const unsigned int b = model.joint_nodes[4 * j + 2 + end];
              const double       G = joint_conductance[j];
              add_to_matrix(a, a, G);
              add_to_matrix(b, b, G);
              add_to_matrix(a, b, -G);
              add_to_matrix(b, a, -G);
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
            add_to_matrix(nodes[a], nodes[b], -J[a][b]);
      });

      // right-hand side: M/dt T_old + loads at t + dt (T-independent
      // parts; Robin's T part in the matrix) + the lagged contact heat
      std::vector<double> rhs(model.n_nodes, 0.);
      for (unsigned int e = first_element; e < end_element; ++e)
        {
          const double c =
            volumetric_heat_capacity[e] * model.reference_area[e] / 12.;
          for (unsigned int a = 0; a < 3; ++a)
            {
              double capacity_T = 0.;
              for (unsigned int b = 0; b < 3; ++b)
                capacity_T += c * (a == b ? 2. : 1.) * T_old[3 * e + b];
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
              add_to_matrix(n, n, h);
            }
        });
      if (lagged_contact_heat.size() > 0)
        for (unsigned int n = first_row; n < last_row; ++n)
          rhs[n] += lagged_contact_heat[n];

      // Dirichlet values at t + dt out of rows and columns (the matrix
      // stays symmetric); a column's value is known on every rank (the
      // condition at the node's reference position)
      const auto held_value = [&](const unsigned int n) {
        return conditions[dirichlet_condition[n]].temperature->value(
          Point<2>(model.x_ref[n], model.y_ref[n]));
      };
      std::vector<double> x(T_old.begin(), T_old.end());
      diagonal.assign(model.n_nodes, 1.);
      for (unsigned int i = first_row; i < last_row; ++i)
        {
          const std::size_t begin = row_start[i - first_row];
          const std::size_t end   = row_start[i - first_row + 1];
          if (dirichlet_node[i])
            {
              double d = 0.;
              for (std::size_t k = begin; k < end; ++k)
                if (row_column[k] == i)
                  d = row_value[k];
                else
                  row_value[k] = 0.;
              d           = d != 0. ? d : 1.;
              x[i]        = held_value(i);
              rhs[i]      = d * x[i];
              diagonal[i] = d;
            }
          else
            for (std::size_t k = begin; k < end; ++k)
              {
                const unsigned int j = row_column[k];
                if (j == i)
                  diagonal[i] = row_value[k];
                else if (dirichlet_node[j])
                  {
                    rhs[i] -= row_value[k] * held_value(j);
                    row_value[k] = 0.;
                  }
              }
        }

      // preconditioned conjugate gradients (Jacobi): x from T_old with the
      // held values; its ghosts are T_old's (current: step())
      std::vector<double> r(model.n_nodes, 0.), z(model.n_nodes, 0.),
        p(model.n_nodes, 0.), q(model.n_nodes, 0.);
      multiply(x, q);
      for (unsigned int i = first_row; i < last_row; ++i)
        {
          r[i] = rhs[i] - q[i];
          z[i] = r[i] / diagonal[i];
          p[i] = z[i];
        }
      std::vector<double> dots;
      dot_products({{rhs.data(), rhs.data()},
                    {r.data(), z.data()},
                    {r.data(), r.data()}},
                   dots);
      const double tolerance =
        parameters.get<DiscreteHeatParameters>().solver_tolerance *
        std::max(1e-300, std::sqrt(dots[0]));
      const unsigned int max_iterations =
        std::max<unsigned int>(1000, model.n_nodes);
      double       rz       = dots[1];
      double       residual = std::sqrt(dots[2]);
      unsigned int it       = 0;
      if (parameters.get<DiscreteHeatParameters>().preconditioner ==
            DiscreteHeatParameters::Preconditioner::amg &&
          std::isfinite(residual) && std::isfinite(dots[0]))
        {
          it =
            solve_with_amg(rhs, x, tolerance, max_iterations, time + time_step);
          residual = 0.; // converged (or thrown)
        }
      while (residual > tolerance || !std::isfinite(residual))
        {
          // the same on every rank (reduced): all stop together
          if (!std::isfinite(residual))
            throw RunError(
              "discrete heat: the implicit system at t = " +
              Utilities::to_string(time + time_step) +
              " s is not finite (CG residual " + std::to_string(residual) +
              " after " + std::to_string(it) +
              " iterations). Likely causes: a boundary, source or initial "
              "temperature function that is not finite somewhere (e.g. an "
              "expression outside its domain), or a material property that "
              "is not. The outputs up to the last output time are intact.");
          if (it >= max_iterations)
            throw RunError(
              "discrete heat: CG did not converge in " + std::to_string(it) +
              " iterations at t = " + std::to_string(time + time_step) +
              " s (residual " + std::to_string(residual) +
              "); Discrete heat/Linear solver tolerance may be too strict.");
          if (partition != nullptr)
            partition->exchange_ghost_node_values(p.data());
          multiply(p, q);
          dot_products({{p.data(), q.data()}}, dots);
          const double alpha = rz / dots[0];
          for (unsigned int i = first_row; i < last_row; ++i)
            {
              x[i] += alpha * p[i];
              r[i] -= alpha * q[i];
              z[i] = r[i] / diagonal[i];
            }
          dot_products({{r.data(), z.data()}, {r.data(), r.data()}}, dots);
          const double beta = dots[0] / rz;
          rz                = dots[0];
          residual          = std::sqrt(dots[1]);
          for (unsigned int i = first_row; i < last_row; ++i)
            p[i] = z[i] + beta * p[i];
          ++it;
        }
      iterations = it;
      for (unsigned int n = first_row; n < last_row; ++n)
        T[n] = x[n];
      if (partition != nullptr)
        partition->exchange_ghost_node_values(T.begin());
    }

    struct DiscreteHeat::AmgCache
    {
      std::vector<std::size_t>          row_start;
      std::vector<unsigned int>         row_column;
      std::vector<double>               row_value;
      IndexSet                          owned;
      TrilinosWrappers::SparseMatrix    matrix;
      TrilinosWrappers::PreconditionAMG amg;
    };

    void
    DiscreteHeat::AmgCacheDeleter::operator()(AmgCache *cache) const
    {
      delete cache;
    }

    unsigned int
    DiscreteHeat::solve_with_amg(const std::vector<double> &rhs,
                                 std::vector<double>       &x,
                                 const double               tolerance,
                                 const unsigned int         max_iterations,
                                 const double               time) const
    {
      // this rank's rows of the assembled (Dirichlet-eliminated) matrix as
      // a distributed Trilinos matrix; columns anywhere
      const unsigned int first_row = 3 * first_element;
      const unsigned int last_row  = 3 * end_element;
      const MPI_Comm     communicator =
        partition != nullptr ? partition->get_communicator() : MPI_COMM_SELF;

      // the matrix and its hierarchy are kept while the rows stay the same
      // on every rank (a fixed step on an unchanged body: most steps);
      // building them is collective, so the ranks decide together
      const bool same_pattern = amg_cache != nullptr &&
                                amg_cache->row_start == row_start &&
                                amg_cache->row_column == row_column;
      const bool same_values =
        same_pattern && amg_cache->row_value == row_value;
      const unsigned int keep = Utilities::MPI::min(same_values  ? 2u :
                                                    same_pattern ? 1u :
                                                                   0u,
                                                    communicator);
      std::vector<types::global_dof_index> columns;
      if (keep == 0)
        {
          amg_cache.reset(new AmgCache());
          IndexSet &owned = amg_cache->owned;
          owned.set_size(model.n_nodes);
          owned.add_range(first_row, last_row);
          owned.compress();
          TrilinosWrappers::SparsityPattern pattern(owned, communicator);
          for (unsigned int i = first_row; i < last_row; ++i)
            {
              const std::size_t begin = row_start[i - first_row];
              const std::size_t end   = row_start[i - first_row + 1];
              columns.assign(row_column.begin() + begin,
                             row_column.begin() + end);
              pattern.add_entries(i, columns.begin(), columns.end(), true);
            }
          pattern.compress();
          amg_cache->matrix.reinit(pattern);
          amg_cache->row_start  = row_start;
          amg_cache->row_column = row_column;
        }
      TrilinosWrappers::SparseMatrix &matrix = amg_cache->matrix;
      if (keep < 2)
        {
          for (unsigned int i = first_row; i < last_row; ++i)
            {
              const std::size_t begin = row_start[i - first_row];
              const std::size_t end   = row_start[i - first_row + 1];
              columns.assign(row_column.begin() + begin,
                             row_column.begin() + end);
              matrix.set(i,
                         columns.size(),
                         columns.data(),
                         row_value.data() + begin,
                         false);
            }
          matrix.compress(VectorOperation::insert);
          amg_cache->row_value = row_value;

          TrilinosWrappers::PreconditionAMG::AdditionalData data;
          data.elliptic              = true;
          data.higher_order_elements = false;
          data.smoother_sweeps       = 2;
          data.aggregation_threshold = 0.02;
          Teuchos::ParameterList              ml_parameters;
          std::unique_ptr<Epetra_MultiVector> constant_modes;
          data.set_parameters(ml_parameters, constant_modes, matrix);
          // aggregates may span ranks (maximal independent sets): a joint
          // couples the nodes of a vertex far more strongly than a
          // triangle does, and aggregates confined to each rank cut those
          // groups at the ranks' borders (contact_conduction refined
          // twice on 2 ranks: 481 CG iterations in 10 steps against 33,
          // the same as on 1 rank)
          ml_parameters.set("aggregation: type", std::string("MIS"));
          amg_cache->amg.initialize(matrix, ml_parameters);
          ++n_amg_setups;
        }
      const IndexSet               &owned = amg_cache->owned;
      TrilinosWrappers::MPI::Vector b(owned, communicator),
        u(owned, communicator);
      for (unsigned int i = first_row; i < last_row; ++i)
        {
          b[i] = rhs[i];
          u[i] = x[i];
        }
      b.compress(VectorOperation::insert);
      u.compress(VectorOperation::insert);

      SolverControl control(max_iterations, tolerance);
      SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
      try
        {
          cg.solve(matrix, u, b, amg_cache->amg);
        }
      catch (const SolverControl::NoConvergence &e)
        {
          throw RunError(
            "discrete heat: CG with AMG did not converge in " +
            std::to_string(e.last_step) +
            " iterations at t = " + Utilities::to_string(time) +
            " s (residual " + std::to_string(e.last_residual) +
            "); Discrete heat/Linear solver tolerance may be too strict, or "
            "try Preconditioner = jacobi.");
        }
      for (unsigned int i = first_row; i < last_row; ++i)
        x[i] = u[i];
      return control.last_step();
    }
  } // namespace discrete
} // namespace tmfdem
