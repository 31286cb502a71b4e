/**
 * @file
 * The rows of a rank and their conjugate gradients (node_row_system.h):
 * pattern, product, chunked dot products, Jacobi CG and the AMG solve on a
 * distributed Trilinos copy of the rows.
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
#include <tmfdem/discrete/node_row_system.h>
#include <tmfdem/discrete/partition.h>

namespace tmfdem
{
  using namespace dealii;

  namespace discrete
  {
    void
    sum_chunks_in_order(std::vector<double>    &partials,
                        const unsigned int      width,
                        const unsigned int      n_chunks,
                        const ElementPartition *partition,
                        std::vector<double>    &totals)
    {
      // each chunk's sums come from one rank; adding zeros is exact
      if (partition != nullptr)
        partition->sum(partials);
      totals.assign(width, 0.);
      for (unsigned int c = 0; c < n_chunks; ++c)
        for (unsigned int i = 0; i < width; ++i)
          totals[i] += partials[c * width + i];
    }

    struct NodeRowSystem::AmgCache
    {
      std::vector<std::size_t>          row_start;
      std::vector<unsigned int>         row_column;
      std::vector<double>               row_value;
      IndexSet                          owned;
      TrilinosWrappers::SparseMatrix    matrix;
      TrilinosWrappers::PreconditionAMG amg;
    };

    NodeRowSystem::NodeRowSystem() = default;

    NodeRowSystem::~NodeRowSystem() = default;

    void
    NodeRowSystem::set_layout(const Layout &new_layout)
    {
      layout = new_layout;
    }

    void
    NodeRowSystem::set_pattern(std::vector<std::vector<unsigned int>> &columns)
    {
      const std::size_t n_rows = columns.size();
      row_start.assign(n_rows + 1, 0);
      row_column.clear();
      for (std::size_t i = 0; i < n_rows; ++i)
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
    NodeRowSystem::zero_values()
    {
      std::fill(row_value.begin(), row_value.end(), 0.);
    }

    void
    NodeRowSystem::add(const unsigned int i,
                       const unsigned int j,
                       const double       value)
    {
      if (!owns_row(i))
        return;
      const unsigned int row   = i - 3 * layout.first_element;
      const auto         begin = row_column.begin() + row_start[row];
      const auto         end   = row_column.begin() + row_start[row + 1];
      const auto         it    = std::lower_bound(begin, end, j);
      Assert(it != end && *it == j, ExcInternalError());
      row_value[it - row_column.begin()] += value;
    }

    void
    NodeRowSystem::impose_held_values(
      const std::vector<bool>                   &held,
      const std::function<double(unsigned int)> &held_value,
      std::vector<double>                       &x,
      std::vector<double>                       &rhs)
    {
      const unsigned int first_row = 3 * layout.first_element;
      const unsigned int last_row  = 3 * layout.end_element;
      diagonal.assign(layout.n_nodes, 1.);
      for (unsigned int i = first_row; i < last_row; ++i)
        {
          const std::size_t begin = row_start[i - first_row];
          const std::size_t end   = row_start[i - first_row + 1];
          if (held[i])
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
                else if (held[j])
                  {
                    rhs[i] -= row_value[k] * held_value(j);
                    row_value[k] = 0.;
                  }
              }
        }
    }

    void
    NodeRowSystem::multiply(const std::vector<double> &x,
                            std::vector<double>       &y) const
    {
      const unsigned int first_row = 3 * layout.first_element;
      for_each_chunk(
        arena_for(layout.n_threads),
        row_start.size() - 1,
        3 * layout.chunk_elements,
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
    NodeRowSystem::dot_products(
      const std::vector<std::pair<const double *, const double *>> &vectors,
      std::vector<double> &results) const
    {
      const unsigned int  width     = vectors.size();
      const unsigned int  first_row = 3 * layout.first_element;
      const unsigned int  rows      = 3 * layout.chunk_elements;
      const unsigned int  offset = layout.first_element / layout.chunk_elements;
      std::vector<double> partials(layout.n_chunks * width, 0.);
      for_each_chunk(arena_for(layout.n_threads),
                     3 * (layout.end_element - layout.first_element),
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
      sum_chunks_in_order(partials,
                          width,
                          layout.n_chunks,
                          layout.partition,
                          results);
    }

    unsigned int
    NodeRowSystem::solve(const std::vector<double> &rhs,
                         std::vector<double>       &x,
                         const double               relative_tolerance,
                         const Preconditioner       preconditioner,
                         const Diagnostics         &diagnostics,
                         const double               time)
    {
      const unsigned int first_row = 3 * layout.first_element;
      const unsigned int last_row  = 3 * layout.end_element;
      // preconditioned conjugate gradients (Jacobi) from x; its ghosts are
      // current
      std::vector<double> r(layout.n_nodes, 0.), z(layout.n_nodes, 0.),
        p(layout.n_nodes, 0.), q(layout.n_nodes, 0.);
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
        relative_tolerance * std::max(1e-300, std::sqrt(dots[0]));
      const unsigned int max_iterations =
        std::max<unsigned int>(1000, layout.n_nodes);
      double       rz       = dots[1];
      double       residual = std::sqrt(dots[2]);
      unsigned int it       = 0;
      if (preconditioner == Preconditioner::amg && std::isfinite(residual) &&
          std::isfinite(dots[0]))
        {
          it       = solve_with_amg(rhs,
                              x,
                              tolerance,
                              max_iterations,
                              diagnostics,
                              time);
          residual = 0.; // converged (or thrown)
        }
      while (residual > tolerance || !std::isfinite(residual))
        {
          // the same on every rank (reduced): all stop together
          if (!std::isfinite(residual))
            throw RunError(
              diagnostics.what + ": the implicit system at t = " +
              Utilities::to_string(time) + " s is not finite (CG residual " +
              std::to_string(residual) + " after " + std::to_string(it) +
              " iterations). " + diagnostics.not_finite_causes);
          if (it >= max_iterations)
            throw RunError(diagnostics.what + ": CG did not converge in " +
                           std::to_string(it) +
                           " iterations at t = " + std::to_string(time) +
                           " s (residual " + std::to_string(residual) + "); " +
                           diagnostics.tolerance_entry + " may be too strict.");
          if (layout.partition != nullptr)
            layout.partition->exchange_ghost_node_values(p.data());
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
      return it;
    }

    unsigned int
    NodeRowSystem::solve_with_amg(const std::vector<double> &rhs,
                                  std::vector<double>       &x,
                                  const double               tolerance,
                                  const unsigned int         max_iterations,
                                  const Diagnostics         &diagnostics,
                                  const double               time)
    {
      // this rank's rows of the assembled (held values imposed) matrix as
      // a distributed Trilinos matrix; columns anywhere
      const unsigned int first_row    = 3 * layout.first_element;
      const unsigned int last_row     = 3 * layout.end_element;
      const MPI_Comm     communicator = layout.partition != nullptr ?
                                          layout.partition->get_communicator() :
                                          MPI_COMM_SELF;

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
          amg_cache       = std::make_unique<AmgCache>();
          IndexSet &owned = amg_cache->owned;
          owned.set_size(layout.n_nodes);
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
          throw RunError(diagnostics.what +
                         ": CG with AMG did not converge in " +
                         std::to_string(e.last_step) +
                         " iterations at t = " + Utilities::to_string(time) +
                         " s (residual " + std::to_string(e.last_residual) +
                         "); " + diagnostics.tolerance_entry +
                         " may be too strict, or try Preconditioner = "
                         "jacobi.");
        }
      for (unsigned int i = first_row; i < last_row; ++i)
        x[i] = u[i];
      return control.last_step();
    }
  } // namespace discrete
} // namespace tmfdem
