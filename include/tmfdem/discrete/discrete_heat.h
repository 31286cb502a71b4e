/**
 * @file
 * Heat in the discrete layer (paper Sec. 3, theory manual chapter "Heat in
 * the discrete layer"): P1 conduction inside every triangle of the exploded
 * mesh (Eqs. 18-20, current configuration), heat exchange across every
 * intact joint k_i (T_B - T_A) with k_i = beta k / h (Eqs. 25-27; switched
 * off when the joint breaks), thermal boundary conditions on boundary ids,
 * explicit (lumped capacity, enforced stable step) or backward Euler
 * (Eq. 22, consistent capacity, CG) time integration, and the heat balance.
 * Anisotropic materials (paper Eqs. 8-9): the conductivity tensor turns with
 * each triangle's rotation, joints conduct with the harmonic mean of the two
 * sides' n.D.n, and the stable step takes the triangles with the largest
 * principal value (theory manual Secs. 1.7, 7.2, 7.3, 7.6).
 *
 * The nodal temperatures are a deal.II Vector indexed like the DoFs of
 * FE_SimplexDGP(1) on the discrete layer's triangulation (node 3e+k).
 *
 * On several MPI ranks (distribute()) each rank advances the nodes of its
 * own triangles (ElementPartition): rates, matrix rows and boundary terms
 * of its triangles, joints and contact pairs, the temperatures of its
 * ghosts from their owners. The implicit step solves with conjugate
 * gradients and a Jacobi preconditioner on the rows of each rank, and every
 * sum (dot products, heat balance) is taken per chunk of triangles and the
 * chunks added in order: temperatures and balance are bitwise the same on
 * any number of ranks and threads (doc/theory.md, "MPI").
 */
#ifndef tmfdem_discrete_discrete_heat_h
#define tmfdem_discrete_discrete_heat_h

#include <deal.II/base/function_parser.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/node_row_system.h>
#include <tmfdem/discrete/temperature_source.h>
#include <vector>

namespace tmfdem
{
  class CheckpointWriter;
  class CheckpointReader;

  namespace discrete
  {
    /** The thermal state and operators of the discrete layer: the
     *  temperature source `discrete heat`. */
    class DiscreteHeat : public TemperatureSource
    {
    public:
      /**
       * Sets up from the materials, `Discrete heat` and `Thermal boundary
       * conditions` of @p parameters for the built @p model. Throws
       * InputError for boundary ids not on the mesh.
       */
      DiscreteHeat(const Parameters &parameters, DiscreteModel &model);
      ~DiscreteHeat() override;

      std::string
      name() const override
      {
        return "discrete heat";
      }

      bool
      sees_cracks() const override
      {
        return true;
      }

      std::string
      describe() const override
      {
        return std::string("discrete heat, ") + (use_implicit ?
                                                   "implicit (backward Euler)" :
                                                   "explicit (forward Euler)");
      }

      /** Threads of the heat rates and the contact search (results do not
       *  depend on it). */
      void
      set_threads(const unsigned int threads) override
      {
        n_threads = std::max(1u, threads);
      }

      /** Sets T(x, y, t0) [C] (reference positions) at every node,
       *  Dirichlet nodes included, each triangle's nodes from the initial
       *  temperature of its material id (Parameters::initial_temperature_of:
       *  body > material > `Initial conditions/Temperature`): the Dirichlet
       *  values act from the first step on. */
      void
      initialise(const double time) override;

      /** Runs on the ranks of @p partition (TemperatureSource::distribute;
       *  on one rank it only takes the chunks of the balance sums). */
      bool
      distribute(ElementPartition &partition) override;

      /** Stable explicit step of the lumped system [s]. */
      double
      stable_time_step() const override;

      /** Advance from @p time by @p time_step with the method of `Discrete
       *  heat/Time integration`. */
      void
      step(const double time, const double time_step) override;

      /** Nodal temperatures [C]. */
      Vector<double> &
      temperature() override
      {
        return T;
      }
      const Vector<double> &
      temperature() const override
      {
        return T;
      }

      /** Heat balance so far. */
      const HeatBalance &
      balance() const override
      {
        return heat_balance;
      }

      /** True for the implicit (backward Euler) method. */
      bool
      implicit() const override
      {
        return use_implicit;
      }

      /** CG iterations of the last implicit step. */
      unsigned int
      last_iterations() const
      {
        return iterations;
      }

      /** Preconditioner = amg: how often this process built the Trilinos
       *  matrix and its multigrid hierarchy (a step whose rows equal the
       *  last step's reuses both). */
      unsigned int
      amg_setups() const
      {
        return rows.amg_setups();
      }

      /**
       * Finds the pairs of triangles that overlap (candidates from a
       * linked-cell search over triangles with a free edge and their
       * neighbours; pairs joined by an intact joint excluded). Call after
       * the geometry or the joints changed; done once by initialise().
       */
      void
      update_contact_pairs() override;
      /** Takes the conducting pairs from @p candidates (the mechanics'
       *  contact search) from now on, instead of its own search. */
      void
      share_contact_candidates(
        const std::vector<ContactPair> *candidates) override
      {
        shared_candidates = candidates;
      }

      /** The conducting pairs (with a triangle of this rank), for the
       *  ghost plan of ElementPartition::build_ghost_plan(). */
      std::vector<ContactPair>
      contact_pair_list() const;

      /** Number of overlapping (conducting) contact pairs (of this rank's
       *  first triangles on several ranks). */
      unsigned int
      n_contact_pairs() const;

      /** Heat rate through each boundary id in the last step [W/m]. */
      const std::map<types::boundary_id, double> &
      last_boundary_rate() const override
      {
        return last_rate;
      }

      /**
       * Sets the discrete temperatures from a continuous P1 field given at
       * the mesh vertices (interpolation: every node takes its vertex's
       * value). @p vertex_values is indexed by vertex index.
       */
      void
      interpolate_from_vertices(const std::vector<double> &vertex_values);

      /** Averages the nodes at each vertex: the continuous P1 field closest
       *  to the discrete one [C], indexed by vertex index. */
      std::vector<double>
      average_to_vertices() const;

      /** Appends the thermal state (temperatures, heat balance, last rates)
       *  to a checkpoint. */
      void
      save(CheckpointWriter &out) const override;
      /** Restores what save() wrote; InputError on a size mismatch. */
      void
      load(CheckpointReader &in) override;

    private:
      /** Heat rates into each node of this rank's triangles from
       *  conduction, joints, contacts, boundary conditions and sources at
       *  time @p time [W/m]. Adds the boundary, source and contact
       *  exchange rates to the chunk sums @p partials (balance layout). */
      void
      heat_rates(const double         time,
                 Vector<double>      &rate,
                 std::vector<double> &partials) const;
      /** Backward Euler: assembles this rank's rows of M/dt + K (+ joints,
       *  contacts, Robin) and the right-hand side @p rhs at t + dt, applies
       *  the Dirichlet values at t + dt (rows and columns), solves into T
       *  (CG, Jacobi) and returns with the ghosts of T current. */
      void
      solve_implicit(const double          time,
                     const double          time_step,
                     const Vector<double> &T_old,
                     const Vector<double> &lagged_contact_heat);
      /** The sparsity of this rank's rows (node 3 first_element on): every
       *  coupling of elements, joints and contacts, set in `rows`. */
      void
      make_row_pattern();

      /** @name Sums taken per chunk of triangles, then the chunks in order
       *  (the same on any number of ranks and threads) */
      ///@{
      /** Entries per chunk in the balance sums: stored heat, source rate,
       *  contact exchange, then per boundary id (balance_slot) the
       *  Neumann/Robin rate, the Dirichlet heat and the Dirichlet rate. */
      unsigned int
      balance_width() const
      {
        return 3 + 3 * balance_slot.size();
      }
      /** Chunk of triangle @p e. */
      unsigned int
      chunk_of(const unsigned int e) const
      {
        return e / chunk_elements;
      }
      /** Sums the chunk sums of all ranks (@p width per chunk) and adds the
       *  chunks in order into @p totals. */
      void
      reduce_chunks(std::vector<double> &partials,
                    const unsigned int   width,
                    std::vector<double> &totals) const;
      ///@}
      /** Calls @p f(edge, node, half_length) for the two nodes of every
       *  boundary edge of this rank whose condition type passes @p use;
       *  half_length is half the edge's current length [m] (the share
       *  lumped on each node). */
      template <typename Use, typename Function>
      void
      for_each_boundary_node(const Use &use, const Function &f) const
      {
        for (std::size_t i = first_edge; i < end_edge; ++i)
          {
            const BoundaryEdge &b = boundary_edges[i];
            if (!use(conditions[b.condition].type))
              continue;
            const unsigned int n0 = 3 * b.element + b.edge;
            const unsigned int n1 = 3 * b.element + (b.edge + 1) % 3;
            const double half     = 0.5 * std::hypot(model.x[n1] - model.x[n0],
                                                 model.y[n1] - model.y[n0]);
            f(b, n0, half);
            f(b, n1, half);
          }
      }
      /** Neumann and Robin conditions (they add heat through the edge). */
      static bool
      flux_condition(const ThermalBoundaryCondition::Type type)
      {
        return type != ThermalBoundaryCondition::Type::dirichlet;
      }

      /** True if node @p n is one of this rank's (its triangle's). */
      bool
      owns_node(const unsigned int n) const
      {
        return n >= 3 * first_element && n < 3 * end_element;
      }
      void
      set_dirichlet_values(const double time);
      void
      set_function_time(const double time) const;

      const Parameters &parameters;
      DiscreteModel    &model;
      Vector<double>    T;
      bool              use_implicit = true;
      /** Discrete heat/Capacity matrix = lumped (implicit steps). */
      bool lumped_implicit_capacity = false;
      /** Discrete heat/Conduction matrix = M-matrix. */
      bool   conduction_m_matrix = false;
      double beta                = 100.;

      std::vector<double> conductivity; ///< per element [W/(m K)]
      /** Largest principal conductivity per element [W/(m K)]. */
      std::vector<double> max_conductivity;
      /** Per element: 1 where the material is anisotropic. */
      std::vector<char> anisotropic;
      /** Reference conductivity tensor (xx, xy, yy) per element [W/(m K)]. */
      std::vector<std::array<double, 3>> conductivity_tensor;
      /** Conductivity matrix of element @p e in the current configuration
       *  [W/(m K)]: isotropic k, or the tensor turned with the element. */
      void
      element_conductivity_matrix(const unsigned int e, double K[3][3]) const;
      std::vector<double> volumetric_heat_capacity; ///< rho c per element
      std::vector<double> lumped_capacity;          ///< per node [J/(m K)]
      std::vector<double>
        joint_conductance; ///< k_i L / 2 per node pair [W/(m K)]

      struct BoundaryEdge
      {
        unsigned int       element, edge;
        unsigned int       condition;
        types::boundary_id id;
      };
      std::vector<BoundaryEdge> boundary_edges;
      std::vector<bool>         dirichlet_node;
      std::vector<unsigned int> dirichlet_condition; ///< per node
      struct ConditionFunctions
      {
        ThermalBoundaryCondition::Type     type;
        std::unique_ptr<FunctionParser<2>> temperature, flux, coefficient,
          ambient;
      };
      std::vector<ConditionFunctions>                 conditions;
      std::vector<std::unique_ptr<FunctionParser<2>>> sources; ///< by material

      /** @name This rank's part (all of it on one rank) */
      ///@{
      ElementPartition *partition = nullptr;
      /** Own triangles [first_element, end_element). */
      unsigned int first_element = 0, end_element = 0;
      /** Joints computed here (those with a triangle of this rank),
       *  ascending. */
      std::vector<unsigned int> local_joints;
      /** Own boundary edges: boundary_edges[first_edge, end_edge). */
      std::size_t first_edge = 0, end_edge = 0;
      /** Triangles per chunk of the sums, and the number of chunks. */
      unsigned int chunk_elements = 512, n_chunks = 0;
      /** Slot of each boundary id in the balance sums. */
      std::map<types::boundary_id, unsigned int> balance_slot;
      ///@}

      /** Implicit: this rank's rows of M/dt + K and their conjugate
       *  gradients. */
      NodeRowSystem rows;
      /** CG iterations of the last implicit step. */
      unsigned int iterations = 0;

      /** Conducting pairs: (contactor, target) triangles. */
      std::vector<std::pair<unsigned int, unsigned int>> contact_pairs;
      /** Candidate pairs of its own linked-cell search (no mechanics). */
      void
      search_contact_candidates(std::vector<ContactPair> &candidates) const;
      /** The mechanics' contact candidates, or nullptr (own search). */
      const std::vector<ContactPair> *shared_candidates   = nullptr;
      double                          contact_conductance = 0.;
      unsigned int                    n_threads           = 1;
      /** Calls @p f(contactor, target, transfer) for every overlapping
       *  pair at the current temperatures. */
      template <typename Function>
      void
      for_each_contact_transfer(const Function &f) const
      {
        compute_contact_transfers();
        for (std::size_t p = 0; p < contact_pairs.size(); ++p)
          if (overlapping[p])
            f(contact_pairs[p].first, contact_pairs[p].second, transfers[p]);
      }
      /** The transfers of all contact pairs at the current temperatures, in
       *  parallel, into `transfers` (`overlapping`: the pair overlaps). */
      void
      compute_contact_transfers() const;
      /** Scratch of compute_contact_transfers(), one entry per pair. */
      mutable std::vector<ContactHeatTransfer> transfers;
      mutable std::vector<char>                overlapping;
      /** Adds the contact heats of T to @p rate and, if given, |Q| of
       *  every pair whose first triangle is this rank's to its chunk in
       *  @p partials (balance layout). */
      void
      add_contact_heat(Vector<double>      &rate,
                       std::vector<double> *partials) const;
      /** Sum of |Q| over the pairs in the last step [W/m]. */
      double                               last_contact_exchange = 0.;
      std::map<types::boundary_id, double> last_rate;

      HeatBalance    heat_balance;
      Vector<double> initial_T;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
