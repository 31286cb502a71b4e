/**
 * @file
 * Heat in the discrete layer in 3D (paper Sec. 3 with tetrahedra; theory
 * manual 5.13): P1 conduction inside every tetrahedron of the exploded
 * mesh in its current configuration (conductivity_matrix<3>()), heat
 * exchange across every intact face joint, G (T_B - T_A) per node pair
 * with G = beta k / h times a third of the face area
 * (joint_pair_conductance<3>(); off once the joint breaks), thermal
 * boundary conditions on the boundary faces (Dirichlet at every node of a
 * held vertex; Neumann and Robin lumped, a third of the current face area
 * per node), volumetric sources, and the heat balance. Time integration
 * as in 2D: forward Euler with the lumped capacity below the stable step,
 * or backward Euler with the consistent capacity, solved by conjugate
 * gradients with a Jacobi preconditioner without assembling a matrix.
 *
 * Every node belongs to one tetrahedron, and each node finds its (at most
 * three) joint partners in a table: rates and matrix products are written
 * per tetrahedron, and every sum (dot products, balance) is taken per
 * chunk of 512 tetrahedra and the chunks added in order, so temperatures
 * and balance are bitwise the same on any number of threads.
 */
#ifndef tmfdem_discrete_tetrahedral_heat_h
#define tmfdem_discrete_tetrahedral_heat_h

#include <deal.II/base/function_parser.h>

#include <map>
#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/temperature_source.h>
#include <tmfdem/discrete/tetrahedron_contact_heat.h>
#include <vector>

namespace tmfdem
{
  class CheckpointWriter;
  class CheckpointReader;

  namespace discrete
  {
    struct TetrahedronContactPair;

    /** The thermal state and operators of the discrete layer in 3D. */
    class TetrahedralHeat
    {
    public:
      /**
       * Sets up from the materials, `Discrete heat` and `Thermal boundary
       * conditions` of @p parameters for the built tetrahedral @p model.
       * Throws InputError for what 3D does not model (anisotropic
       * conductivity) and for boundary ids not on the mesh.
       */
      TetrahedralHeat(const Parameters &parameters, DiscreteModel &model);

      /** Threads of the rates and the solver (results do not depend on
       *  it). */
      void
      set_threads(const unsigned int threads)
      {
        n_threads = threads > 0 ? threads : 1;
      }

      /**
       * Where the contact heat finds its pairs: with @p pairs, the
       * mechanics' contact search (the list kept up to date by it, read at
       * every step at the current geometry); with nullptr and
       * @p moving_geometry false (the heat alone, the default), a search of
       * its own on the fixed geometry, once; with nullptr and a moving
       * geometry (thermo-mechanics without contact: pieces pass through
       * each other), no contact heat.
       */
      void
      set_contact_candidates(const std::vector<TetrahedronContactPair> *pairs,
                             const bool moving_geometry)
      {
        shared_pairs = pairs;
        if (pairs == nullptr && moving_geometry)
          contact_conductance = 0.;
      }

      /** Pairs of tetrahedra that exchanged heat in the last step. */
      std::size_t
      n_contact_pairs() const
      {
        return contact_pairs.size();
      }

      /** Sets T(x, y, z, @p time) [C] at every node from the initial
       *  temperature of its tetrahedron's material (body > material >
       *  `Initial conditions/Temperature`), Dirichlet nodes included (their
       *  values act from the first step on, as in 2D). */
      void
      initialise(const double time);

      /** Stable step of the forward Euler method [s]: 2 / lambda_max of
       *  C^-1 (K + joints + Robin + contact) bounded by Gershgorin's rows
       *  (the conduction, joints and Robin at the reference geometry, the
       *  contact of the current pairs). */
      double
      stable_time_step() const;

      /** Advances from @p time [s] by @p time_step [s] with `Discrete
       *  heat/Time integration`, at the current geometry and joints. */
      void
      step(const double time, const double time_step);

      /** True for backward Euler. */
      bool
      implicit() const
      {
        return use_implicit;
      }

      /** Nodal temperatures [C] (node 4 e + k is vertex k of tetrahedron
       *  e). */
      const std::vector<double> &
      temperature() const
      {
        return T;
      }

      /** Heat balance so far [J]. */
      const HeatBalance &
      balance() const
      {
        return heat_balance;
      }

      /** Heat rate into the body through each boundary id in the last
       *  step [W]. */
      const std::map<types::boundary_id, double> &
      last_boundary_rate() const
      {
        return last_rate;
      }

      /** Conjugate gradient iterations of the last implicit step. */
      unsigned int
      last_iterations() const
      {
        return iterations;
      }

      /** Mean of the four nodal temperatures of tetrahedron @p e [C]. */
      double
      element_temperature(const unsigned int e) const
      {
        return 0.25 * (T[4 * e] + T[4 * e + 1] + T[4 * e + 2] + T[4 * e + 3]);
      }

      /** Appends the thermal state (temperatures, heat balance, last
       *  rates, last iterations) to @p out. */
      void
      save(CheckpointWriter &out) const;
      /** Restores what save() wrote; InputError on a size mismatch. */
      void
      load(CheckpointReader &in);

    private:
      /** A pair of tetrahedra that exchanges heat: the first is the
       *  contactor of the transfer, and their contact geometry. */
      struct HeatContactPair
      {
        unsigned int                first, second;
        TetrahedronContactInterface interface;
      };
      /** The pairs that overlap at the current geometry, from the shared
       *  candidates or (heat alone, once) a search of its own. */
      void
      update_contact_pairs();
      /** Adds the contact heat of every pair at the nodal temperatures
       *  @p temperatures [C] to @p rate [W], in pair order; returns the sum
       *  of |Q| [W]. */
      double
      add_contact_heat(const std::vector<double> &temperatures,
                       std::vector<double>       &rate) const;
      /** Whether the contact heat enters the implicit matrix (the
       *  temperature-difference model; the paper literal one is lagged). */
      bool
      contact_in_matrix() const
      {
        return contact_model == ContactHeatModel::temperature_difference &&
               !contact_pairs.empty();
      }

      /** A boundary face with a thermal condition. */
      struct BoundaryFace
      {
        unsigned int       element;   ///< tetrahedron
        unsigned int       face;      ///< deal.II's face (opposite 3 - face)
        unsigned int       condition; ///< index into conditions
        types::boundary_id id;
      };
      /** The functions of one thermal boundary condition, of (x, y, z, t). */
      struct ConditionFunctions
      {
        ThermalBoundaryCondition::Type     type;
        std::unique_ptr<FunctionParser<3>> temperature, flux;
        std::unique_ptr<FunctionParser<3>> coefficient, ambient;
      };

      /** The conductivity matrices of the tetrahedra at the current
       *  geometry (element_matrix). */
      void
      update_element_matrices();
      /** Heat rates into every node at time @p time [W] from conduction,
       *  joints, sources and Neumann/Robin faces; adds the source and
       *  boundary rates to the chunk sums @p partials. */
      void
      heat_rates(const double         time,
                 std::vector<double> &rate,
                 std::vector<double> &partials);
      /** Calls @p row(n, p_n) for every node n with p = (element_matrix +
       *  intact joints) @p x, per tetrahedron on the threads (each row its
       *  own node's). */
      template <typename Row>
      void
      for_each_row(const std::vector<double> &x, const Row &row) const;
      /** y = (M/dt + K + joints + Robin) x on the free nodes, 0 on the
       *  Dirichlet nodes (implicit step). */
      void
      apply(const std::vector<double> &x, std::vector<double> &y) const;
      /** Backward Euler: solves for T at @p time + @p time_step. */
      void
      solve_implicit(const double               time,
                     const double               time_step,
                     const std::vector<double> &T_old,
                     const std::vector<double> &lagged_contact_heat);
      /** The heat source of tetrahedron @p e lumped on each of its four
       *  nodes, q V / 4 with q at the centroid at the functions' time [W]. */
      double
      nodal_source(const unsigned int e) const;
      /** Sum over the chunks, in order, of f(begin, end) on the threads. */
      template <typename Function>
      double
      chunked_sum(const Function &f) const;
      /** Calls f(face, node, third) for the three nodes of every boundary
       *  face with a flux condition, third = a third of the face's current
       *  area [m^2]. */
      template <typename Function>
      void
      for_each_flux_node(const Function &f) const;
      void
      set_dirichlet_values(const double time);
      void
      set_function_time(const double time) const;

      const Parameters &parameters;
      DiscreteModel    &model;
      bool              use_implicit = true;
      /** Discrete heat/Capacity matrix = lumped (implicit steps). */
      bool lumped_implicit_capacity = false;
      /** Discrete heat/Conduction matrix = M-matrix. */
      bool                          conduction_m_matrix = false;
      double                        beta                = 1000.;
      double                        tolerance           = 1e-12;
      unsigned int                  n_threads           = 1;
      unsigned int                  iterations          = 0;
      static constexpr unsigned int chunk_elements      = 512;
      unsigned int                  n_chunks            = 0;

      std::vector<double> T;
      std::vector<double> conductivity;             ///< per element [W/(m K)]
      std::vector<double> volumetric_heat_capacity; ///< rho c [J/(m^3 K)]
      std::vector<double> lumped_capacity;          ///< per node [J/K]
      /** Per element: the 4 x 4 matrix of the step (K, or M/dt + K). */
      std::vector<double> element_matrix;
      /** Per node and slot (the node's three faces): the joined node on
       *  the other side, or -1, and the pair conductance [W/K]. */
      std::vector<int>    partner;
      std::vector<double> partner_conductance;
      /** Per node: the joint of each slot (its status switches it off). */
      std::vector<int> partner_joint;
      /** Per node: Robin's h A / 3 at the end of the implicit step [W/K]. */
      std::vector<double> robin_diagonal;
      /** Per node: Gershgorin's row sum of conduction, joints and Robin
       *  over the capacity [1/s] (stable_time_step(), computed once). */
      mutable std::vector<double> row_bound;

      /** `Discrete heat/Contact conductance` h_c [W/(m^2 K)] (0: no
       *  contact heat) and `Contact heat model`. */
      double           contact_conductance = 0.;
      ContactHeatModel contact_model = ContactHeatModel::temperature_difference;
      /** The mechanics' pair list, or nullptr (a search of its own). */
      const std::vector<TetrahedronContactPair> *shared_pairs = nullptr;
      /** Whether the pairs of the own search are known (the geometry of
       *  the heat alone does not change). */
      bool                         own_pairs_found = false;
      std::vector<HeatContactPair> contact_pairs;

      std::vector<std::unique_ptr<FunctionParser<3>>> sources; ///< per material
      std::vector<ConditionFunctions>                 conditions;
      std::vector<BoundaryFace>                       boundary_faces;
      std::vector<char>                               dirichlet_node;
      std::vector<unsigned int>                       dirichlet_condition;
      /** Boundary id -> its slot in the balance sums. */
      std::map<types::boundary_id, unsigned int> balance_slot;
      HeatBalance                                heat_balance;
      std::map<types::boundary_id, double>       last_rate;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
