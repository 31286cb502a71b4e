/**
 * @file
 * A rank's rows of a sparse symmetric system over the discrete layer's
 * nodes and its solution by conjugate gradients, reproducible on any number
 * of ranks and threads. The implicit discrete heat (discrete_heat.h)
 * assembles into it; it knows nothing of heat.
 */
#ifndef tmfdem_discrete_node_row_system_h
#define tmfdem_discrete_node_row_system_h

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    class ElementPartition;

    /**
     * Sums chunk sums in chunk order: @p partials holds @p width sums per
     * chunk of triangles (@p n_chunks chunks of the whole mesh, each
     * computed by one rank); they are summed over the ranks of
     * @p partition (null on one rank; adding zeros is exact) and the chunks
     * added in order into @p totals. The result is bitwise the same on any
     * number of ranks and threads.
     */
    void
    sum_chunks_in_order(std::vector<double>    &partials,
                        const unsigned int      width,
                        const unsigned int      n_chunks,
                        const ElementPartition *partition,
                        std::vector<double>    &totals);

    /**
     * Rows of one rank of a sparse symmetric matrix over the nodes of the
     * discrete layer (node 3e+k is vertex k of triangle e; the rank's rows
     * are the nodes of its triangles), in compressed rows with the columns
     * sorted, and its solution by conjugate gradients.
     *
     * Reproducible: a row's product adds its entries in column order, every
     * dot product is summed per chunk of triangles and the chunks added in
     * order (sum_chunks_in_order()), so with the Jacobi preconditioner the
     * iterates are bitwise the same on any number of ranks and threads.
     * With algebraic multigrid (Trilinos ML on a distributed copy of the
     * rows) they agree to the solver tolerance.
     */
    class NodeRowSystem
    {
    public:
      /** Which rows are this rank's and how its sums are chunked. */
      struct Layout
      {
        unsigned int n_nodes        = 0;   ///< of the whole mesh
        unsigned int first_element  = 0;   ///< this rank's triangles
        unsigned int end_element    = 0;   ///< one past the last
        unsigned int chunk_elements = 512; ///< triangles per chunk
        unsigned int n_chunks       = 0;   ///< chunks of the whole mesh
        unsigned int n_threads      = 1;
        /** Ghost exchange and sums over ranks; null on one rank. */
        ElementPartition *partition = nullptr;
      };

      /** Preconditioner of the conjugate gradients. */
      enum class Preconditioner
      {
        jacobi, ///< the diagonal; bitwise the same on any rank count
        amg     ///< algebraic multigrid (Trilinos ML)
      };

      NodeRowSystem();
      ~NodeRowSystem();

      /** Sets the layout (before assembling; a change of the rank's rows
       *  needs a new pattern, clear_pattern()). */
      void
      set_layout(const Layout &layout);

      /** True once set_pattern() has given the rows their columns. */
      bool
      has_pattern() const
      {
        return !row_start.empty();
      }
      /** Forgets the pattern (the couplings changed). */
      void
      clear_pattern()
      {
        row_start.clear();
      }
      /** The columns of each of this rank's rows (row i of the rank is node
       *  3 first_element + i), in any order and with repetitions; sorted
       *  and made unique here. All values zero. */
      void
      set_pattern(std::vector<std::vector<unsigned int>> &columns);

      /** True if node @p n is one of this rank's rows. */
      bool
      owns_row(const unsigned int n) const
      {
        return n >= 3 * layout.first_element && n < 3 * layout.end_element;
      }
      /** Sets every value to zero (the pattern stays). */
      void
      zero_values();
      /** Adds @p value to entry (i, j) if row i is this rank's; (i, j) must
       *  be in the pattern. */
      void
      add(const unsigned int i, const unsigned int j, const double value);

      /**
       * Imposes held values: for every row i of this rank with @p held[i],
       * x[i] = held_value(i), rhs[i] = A_ii x[i] and the rest of the row
       * zero; in the other rows the held columns move to the right-hand
       * side (A_ij held_value(j) subtracted from rhs[i]) and are zeroed, so
       * the matrix stays symmetric. A held column's value must be known on
       * every rank. Also takes the diagonal for the preconditioner.
       */
      void
      impose_held_values(const std::vector<bool>                   &held,
                         const std::function<double(unsigned int)> &held_value,
                         std::vector<double>                       &x,
                         std::vector<double>                       &rhs);

      /** What a failed solve's message says about the system. */
      struct Diagnostics
      {
        /** The system's owner, first in every message. */
        std::string what;
        /** Likely causes of a system that is not finite. */
        std::string not_finite_causes;
        /** The prm entry of the relative tolerance. */
        std::string tolerance_entry;
      };

      /**
       * Solves A x = @p rhs on this rank's rows by preconditioned conjugate
       * gradients from @p x (its ghost entries current) until the residual
       * is below @p relative_tolerance times |rhs|; returns the iterations
       * and leaves this rank's rows of @p x solved (its ghosts not
       * exchanged). RunError (from @p diagnostics, naming the time
       * @p time [s]) where the system is not finite or the solver does not
       * converge in max(1000, n_nodes) iterations; the ranks stop together.
       */
      unsigned int
      solve(const std::vector<double> &rhs,
            std::vector<double>       &x,
            const double               relative_tolerance,
            const Preconditioner       preconditioner,
            const Diagnostics         &diagnostics,
            const double               time);

      /** How often this process built the Trilinos matrix and its
       *  multigrid hierarchy (a solve whose rows equal the last one's
       *  reuses both). */
      unsigned int
      amg_setups() const
      {
        return n_amg_setups;
      }

    private:
      /** y = A x on this rank's rows (x with current ghosts). */
      void
      multiply(const std::vector<double> &x, std::vector<double> &y) const;
      /** Dot products a_i . b_i over this rank's rows, summed per chunk and
       *  in chunk order over all ranks. */
      void
      dot_products(
        const std::vector<std::pair<const double *, const double *>> &vectors,
        std::vector<double> &results) const;
      /** CG preconditioned by algebraic multigrid on a distributed Trilinos
       *  copy of the rows, from @p x to @p tolerance (absolute); writes
       *  this rank's rows of @p x; returns the iterations. */
      unsigned int
      solve_with_amg(const std::vector<double> &rhs,
                     std::vector<double>       &x,
                     const double               tolerance,
                     const unsigned int         max_iterations,
                     const Diagnostics         &diagnostics,
                     const double               time);

      Layout                    layout;
      std::vector<std::size_t>  row_start;
      std::vector<unsigned int> row_column;
      std::vector<double>       row_value;
      /** The diagonal for the Jacobi preconditioner (all nodes). */
      std::vector<double> diagonal;

      /** The rows, Trilinos matrix and AMG hierarchy of the last AMG
       *  solve, reused while the rows stay the same. */
      struct AmgCache;
      std::unique_ptr<AmgCache> amg_cache;
      unsigned int              n_amg_setups = 0;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
