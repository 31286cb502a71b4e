/**
 * @file
 * Parameters of the discrete (FDEM) layer: subsection `Discrete mechanics`
 * (time step, penalties, damping, contact, friction, softening law,
 * heterogeneity, gravity, threads) and subsection `Discrete bodies`
 * (which material ids move freely, are fixed or move with a prescribed
 * velocity, and their initial velocities).
 */
#ifndef tmfdem_discrete_discrete_parameters_h
#define tmfdem_discrete_discrete_parameters_h

#include <deal.II/base/types.h>

#include <array>
#include <string>
#include <tmfdem/base/parameters.h>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/vector_instructions.h>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace tmfdem
{
  using namespace dealii;

  /** Subsection `Discrete mechanics`. */
  struct DiscreteMechanicsParameters
  {
    double time_step     = 0.;  ///< [s]; 0: safety factor x stable step
    double safety_factor = 0.5; ///< fraction of the stable step [-]
    double joint_normal_penalty_factor     = 10.; ///< p_n / E [-]
    double joint_tangential_penalty_factor = 10.; ///< p_t / E [-]
    /** Stiffen each triangle by its joints' compliance (joint_compliance.h).
     */
    bool joint_compliance_compensation = true;
    /** ... and by the tensor of that compliance, not only its isotropic
     *  average (an anisotropic correction per triangle). */
    bool   anisotropic_joint_compliance_compensation = true;
    double contact_penalty_factor                    = 10.; ///< p_c / E [-]
    double contact_tangential_penalty_factor         = 1.;  ///< p_ct / E [-]
    double friction_coefficient                      = 0.5; ///< mu [-]
    /** Memory slip L of the regularised friction [m]; 0: plain Coulomb. */
    double friction_memory_slip = 1e-7;
    /** Rate effect a of the regularised friction [-]. */
    double friction_rate_effect = 0.01;
    /** Reference slip rate v0 of the rate effect [m/s]. */
    double friction_reference_slip_rate = 1e-6;
    /** The target's share of the normal contact force as the exact
     *  gradient of the contact energy (false: at the contact points). */
    bool contact_potential_gradient_on_target = true;
    /** The faces of a broken joint touch with at most the joint's
     *  compressive stiffness (false: with the contact penalty). */
    bool contact_broken_faces_at_joint_stiffness = true;
    /** Softening law (cohesive_law.h registry). */
    discrete::SofteningLaw softening_law = discrete::SofteningLaw::munjiza;
    double damping_ratio = 1.; ///< modal ratio of the highest element mode [-]
    double mass_damping  = 0.; ///< c of -c m v [1/s]
    /** Mass scaling: every node's mass is this factor times the
     *  material's (the inertia only: gravity keeps the physical weight,
     *  the heat capacity is unchanged) [-]; 1: none. */
    double              mass_scaling_factor = 1.;
    std::vector<double> gravity             = {0., 0.}; ///< [m/s^2]
    /** Gravity grows linearly from 0 over this time from t = 0 [s]; 0: at
     *  once. */
    double       gravity_ramp_time      = 0.;
    double       contact_buffer         = 0.;    ///< [m]; 0: 0.25 x smallest h
    unsigned int threads                = 0;     ///< 0: all cores
    bool         allow_oversubscription = false; ///< threads beyond the cores
    /** Instruction set of the explicit loop's batches, resolved from the
     *  entry (auto: the widest this processor has). */
    discrete::VectorInstructions vector_instructions =
      discrete::VectorInstructions::sse2;
    /** Vector instructions = auto (the set then also depends on the mesh:
     *  discrete::vector_instructions_for_mesh()). */
    bool vector_instructions_auto = true;
    /** Number the triangles along a Hilbert curve (cell_order.h); false:
     *  in the mesh's order. */
    bool hilbert_curve_numbering = true;
    /** How joint strengths scatter (Heterogeneity). */
    enum class Heterogeneity
    {
      none,
      weibull, ///< Weibull factors of mean 1, modulus weibull_modulus
      normal   ///< normal factors of mean 1, coefficient_of_variation
    };
    Heterogeneity heterogeneity            = Heterogeneity::none;
    double        weibull_modulus          = 10.; ///< m [-]
    double        coefficient_of_variation = 0.1; ///< normal: std/mean [-]
    /** How the thermal expansion coefficient scatters from triangle to
     *  triangle (Expansion heterogeneity). */
    enum class ExpansionHeterogeneity
    {
      none,
      normal ///< normal factors of mean 1, expansion_coefficient_of_variation
    };
    ExpansionHeterogeneity expansion_heterogeneity =
      ExpansionHeterogeneity::none;
    /** normal expansion factors: std/mean [-] */
    double       expansion_coefficient_of_variation = 0.3;
    unsigned int random_seed                        = 1;
    unsigned int max_steps                          = 0; ///< 0: no limit
    bool         contact                            = true;
    /** Pre-existing fractures: segments (x0, y0, x1, y1) [m]; the joints
     *  lying on them start broken. */
    std::vector<std::array<double, 4>> initial_cracks;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** Subsection `Discrete heat`. */
  struct DiscreteHeatParameters
  {
    /** Name of a registered discrete::TemperatureSource. */
    std::string temperature_source = "discrete heat";
    /** Temperature source = continuum heat goes on past broken joints. */
    bool accept_continuum_source_at_broken_joints = false;
    /** Time integration of the discrete heat. */
    enum class TimeIntegration
    {
      implicit,
      explicit_euler
    };
    TimeIntegration time_integration = TimeIntegration::implicit;
    /** Capacity matrix of the implicit step: consistent (the default) or
     *  lumped (no overshoot of the initial or boundary temperatures at
     *  steps much shorter than h^2 / kappa). */
    bool lumped_implicit_capacity = false;
    /** Conduction matrix of each element: consistent (the default) or an
     *  M-matrix (positive couplings moved onto the diagonal:
     *  make_conduction_m_matrix()). */
    bool   conduction_m_matrix      = false;
    double joint_conductance_factor = 1000.; ///< beta [-]
    double contact_conductance      = 1e4;   ///< h_c [W/(m^2 K)]
    double safety_factor            = 0.9;   ///< explicit [-]
    double solver_tolerance         = 1e-12; ///< relative
    /** Preconditioner of the implicit step's conjugate gradients. */
    enum class Preconditioner
    {
      jacobi, ///< the diagonal; bitwise the same on any rank count
      amg     ///< algebraic multigrid (Trilinos ML), distributed matrix
    };
    Preconditioner preconditioner                    = Preconditioner::jacobi;
    unsigned int   mechanical_steps_per_thermal_step = 0; ///< 0: automatic
    /** How heat and mechanics take turns (Coupling). */
    enum class Coupling
    {
      dynamic,     ///< multi-rate: a thermal step every n mechanical steps
      quasi_static ///< a thermal step, then the mechanics relaxes
    };
    Coupling coupling             = Coupling::dynamic;
    double   relaxation_tolerance = 1e-6; ///< kinetic / strain energy
    bool     relaxation_cap_is_error =
      false; ///< stop when a relaxation hits the cap
    double relaxation_force_tolerance = 1e-3; ///< |out-of-balance| / |internal|
    /** Quasi-static: start of each relaxation, none (the last relaxed
     *  state) or extrapolate (last state + its last increment scaled by
     *  the ratio of the thermal steps). */
    enum class RelaxationPredictor
    {
      none,
      extrapolate
    };
    RelaxationPredictor relaxation_predictor = RelaxationPredictor::none;
    /** Quasi-static: mass (Discrete mechanics/Mass damping only) or
     *  kinetic (velocities set to zero at every peak of the kinetic
     *  energy, besides). */
    enum class RelaxationDamping
    {
      mass,
      kinetic
    };
    RelaxationDamping relaxation_damping = RelaxationDamping::mass;
    /** Quasi-static, kinetic damping: physical time of mechanical steps
     *  for which the velocity resets pause once a joint breaks in a
     *  relaxation (the fracture event runs with inertia) [s]; 0: never. */
    double fracture_event_duration = 0.;
    /** Quasi-static: thermal step n = Time step x growth^n [-]. */
    double thermal_step_growth = 1.;
    /** Quasi-static: cap of the growing thermal step, 0 = none [s]. */
    double maximum_thermal_step = 0.;
    /** Quasi-static: largest predicted rise of the joints' strength
     *  utilisation per thermal step [-]; 0: off. */
    double maximum_utilisation_change = 0.01;
    /** Quasi-static: the fraction of its margin to the peak, 1 - U, that a
     *  joint may use up per thermal step where that is more than
     *  maximum_utilisation_change [-]; 0: the change alone. */
    double utilisation_margin_fraction = 0.;
    /** Quasi-static: most joints that may break in one thermal step (the
     *  next step shrinks where more did; a step with more than twice this
     *  many is re-run shorter) [-]; 0: off. */
    unsigned int maximum_broken_joints_per_step = 2;
    /** Quasi-static: shortest thermal step of the step control; 0: 1e-3
     *  Time step [s]. */
    double minimum_thermal_step = 0.;
    /** Driving term of the contact heat (`Contact heat model`). */
    discrete::ContactHeatModel contact_heat_model =
      discrete::ContactHeatModel::temperature_difference;

    /** The prm names of the options (summary.json, messages). */
    std::string
    coupling_name() const;
    std::string
    time_integration_name() const;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /** One body: the cells of some material ids and how they move. */
  struct DiscreteBody
  {
    enum class Motion
    {
      free,
      fixed,
      velocity
    };
    std::string                     name;       ///< for messages
    unsigned int                    number = 0; ///< N of Body N
    std::vector<types::material_id> material_ids;
    Motion                          motion     = Motion::free;
    std::string                     velocity_x = "0"; ///< v_x(t) [m/s]
    std::string                     velocity_y = "0"; ///< v_y(t) [m/s]
    std::string initial_velocity_x = "0"; ///< v_x(x, y) at start [m/s]
    std::string initial_velocity_y = "0"; ///< v_y(x, y) at start [m/s]
    /** v_z(t) (Mesh/Dimension = 3) [m/s]. */
    std::string velocity_z = "0";
    /** v_z(x, y, z) at start (Mesh/Dimension = 3) [m/s]. */
    std::string initial_velocity_z = "0";
    /** T(x, y) at the start time [C]; empty: the materials' or the global
     *  initial temperature (Parameters::initial_temperature_of()). */
    std::string initial_temperature;
  };

  /** Subsection `Discrete bodies`: up to max_bodies `Body <n>`. Cells of
   *  material ids named by no body move freely with zero initial velocity. */
  struct DiscreteBodyParameters
  {
    static constexpr unsigned int max_bodies = 8;
    std::vector<DiscreteBody>     bodies;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
    /** After all sections are parsed: the bodies' initial temperatures
     *  become overrides of @p parameters (Parameters::initial_temperature_of);
     *  a body and one of its materials both setting one is refused. */
    void
    complete(Parameters &parameters) const;
  };
} // namespace tmfdem

#endif
