/**
 * @file
 * What drives the discrete layer from outside: bodies (Discrete bodies:
 * free, fixed or driven with a velocity), gravity, and the mechanical
 * boundary conditions on boundary ids (Mechanical boundary conditions:
 * velocity, displacement, rollers, traction), turned into per-node data the
 * fused node update (ExplicitSolver::update_nodes) reads, and the reactions
 * it sums.
 */
#ifndef tmfdem_discrete_drivers_h
#define tmfdem_discrete_drivers_h

#include <deal.II/base/function_parser.h>

#include <algorithm>
#include <array>
#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * When the imposed motions are evaluated (ExplicitSolver supplies it):
     * in dynamic runs the step's own times; in quasi-static coupling the
     * thermal time, the motion of one thermal step spread over the first
     * relaxation steps.
     */
    struct ImposedMotionClock
    {
      double velocity_time     = 0.; ///< velocities: at mid step [s]
      double displacement_time = 0.; ///< displacements: reached then [s]
      double traction_time     = 0.; ///< tractions [s]
      /** Factor from a physical velocity to the velocity of this step [-]. */
      double velocity_scale = 1.;
      /** Steps left to reach the displacement target [-]. */
      double steps_to_target = 1.;
      double time_step       = 0.; ///< the explicit step [s]
    };

    /** Bodies, gravity and boundary conditions of a discrete run. */
    class Drivers
    {
    public:
      /** Most bodies and conditions whose reactions are summed per chunk. */
      static constexpr unsigned int max_bodies = 8;
      static constexpr unsigned int max_conditions =
        MechanicalBoundaryParameters::max_conditions;

      /** One node on a boundary edge with a condition. */
      struct NodeCondition
      {
        unsigned int node;
        unsigned int condition;          ///< index into `conditions`
        bool         prescribed[2];      ///< velocity component prescribed
        double       velocity[2];        ///< prescribed velocity [m/s]
        double       force[2];           ///< traction force [N/m]
        double       traction_length;    ///< reference length share [m]
        int          traction_condition; ///< its traction condition, or -1
      };
      /** The functions of one condition. */
      struct ConditionFunctions
      {
        MechanicalBoundaryCondition::Type                 type;
        std::array<std::unique_ptr<FunctionParser<2>>, 2> value;
        std::array<bool, 2> time_dependent{{false, false}};
      };

      /** Bodies of Discrete bodies: element and node body indices in
       *  @p model, initial velocities of free bodies, gravity. */
      void
      setup_bodies(const Parameters &parameters, DiscreteModel &model);
      /** Conditions of Mechanical boundary conditions on the nodes of
       *  boundary edges (of free bodies), evaluated at @p clock. */
      void
      setup_boundary_conditions(const Parameters         &parameters,
                                const DiscreteModel      &model,
                                const ImposedMotionClock &clock);
      /** Prescribed velocities and traction forces at @p clock (the current
       *  positions of @p model for displacement targets). */
      void
      evaluate_boundary_conditions(const DiscreteModel      &model,
                                   const ImposedMotionClock &clock);
      /** Driven bodies' velocities at @p clock. */
      void
      evaluate_body_velocities(const ImposedMotionClock &clock);

      /** Does anything impose a motion (velocity or displacement conditions,
       *  driven bodies)? */
      bool
      imposes_motion() const;
      /** Do the conditions change during the run (displacements, functions
       *  of t)? */
      bool
      conditions_change() const
      {
        return boundary_conditions_change;
      }
      /** Is node @p n free to move (no fixed or driven body)? */
      bool
      node_is_free(const unsigned int n) const
      {
        const unsigned char b = node_body[n];
        return b == no_body || body_motion[b] == DiscreteBody::Motion::free;
      }
      /** Is component @p d of node @p n prescribed by a condition? */
      bool
      prescribed(const unsigned int n, const unsigned int d) const
      {
        const int slot = node_condition_slot[n];
        return slot >= 0 && node_conditions[slot].prescribed[d];
      }
      /** Per element: its body if that body is fixed or driven, else
       *  no_body (elements of one such group never meet in contact). */
      std::vector<unsigned char>
      rigid_groups(const DiscreteModel &model) const;
      /** Zero the reactions before a step's sums. */
      void
      clear_reactions();

      /** @name Data the fused node update reads (flat, per node) */
      /** @{ */
      std::vector<unsigned char>         node_body; ///< body index or no_body
      std::vector<DiscreteBody::Motion>  body_motion;
      std::vector<std::array<double, 2>> body_velocity_now; ///< [m/s]
      std::array<double, 2>              gravity{{0., 0.}}; ///< [m/s^2]
      /** Gravity grows linearly from 0 over this time [s]; 0: at once. */
      double gravity_ramp_time = 0.;

      /** The share of Gravity acting at time @p t [s] (Gravity ramp
       *  time): min(1, t / ramp), 1 without a ramp. */
      double
      gravity_share(const double t) const
      {
        return gravity_ramp_time > 0. ? std::min(1., t / gravity_ramp_time) :
                                        1.;
      }
      /** Per node: slot into node_conditions, or -1. */
      std::vector<int>                node_condition_slot;
      std::vector<NodeCondition>      node_conditions;
      std::vector<ConditionFunctions> conditions;
      /** @} */

      /** @name Reactions of the last step [N/m] */
      /** @{ */
      std::vector<std::array<double, 2>> body_reaction;
      std::vector<std::array<double, 2>> condition_reaction;
      /** @} */

    private:
      /** Velocity x, y of each body (two per body). */
      std::vector<std::unique_ptr<FunctionParser<2>>> body_velocity;
      bool boundary_conditions_change = false;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
