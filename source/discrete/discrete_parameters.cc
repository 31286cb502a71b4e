#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <set>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/temperature_source.h>

namespace tmfdem
{
  namespace
  {
    /** The names of a registry (name, value pairs) as a
     *  Patterns::Selection: "a|b|c". */
    template <typename Registry>
    std::string
    selection_of(const Registry &registry)
    {
      std::string names;
      for (const auto &entry : registry)
        names += (names.empty() ? "" : "|") + entry.first;
      return names;
    }

    // the discrete layer's subsections, declared and parsed with the others
    const bool registered =
      register_parameter_section<DiscreteMechanicsParameters>(
        "Discrete mechanics") &&
      register_parameter_section<DiscreteBodyParameters>("Discrete bodies") &&
      register_parameter_section<DiscreteHeatParameters>("Discrete heat");

    void
    require_positive(const double value, const std::string &entry)
    {
      if (!(value > 0.))
        throw InputError("Discrete mechanics/" + entry + " = " +
                         Utilities::to_string(value) + ": must be > 0.");
    }
  } // namespace

  void
  DiscreteMechanicsParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Discrete mechanics");
    prm.declare_entry("Time step",
                      "0",
                      Patterns::Double(0.),
                      "Explicit time step [s]; 0: Safety factor times the "
                      "stable step computed from the mesh and penalties. A "
                      "step above the stable step is refused.");
    prm.declare_entry("Safety factor",
                      "0.5",
                      Patterns::Double(1e-6, 1.),
                      "Fraction of the stable step used when Time step = 0 "
                      "[-].");
    prm.declare_entry("Joint normal penalty factor",
                      "10",
                      Patterns::Double(0.),
                      "Joint normal penalty p_n = factor x E [Pa]; the "
                      "initial joint stiffness is p_n / h [Pa/m], h the "
                      "joint length.");
    prm.declare_entry("Joint tangential penalty factor",
                      "10",
                      Patterns::Double(0.),
                      "Joint tangential penalty p_t = factor x E [Pa].");
    prm.declare_entry(
      "Joint compliance compensation",
      "true",
      Patterns::Bool(),
      "true: every triangle is made stiffer by the compliance of its own "
      "intact joints (their lengths and penalties, at set-up), so that a "
      "triangle in series with its joints has the material's E and nu "
      "(isotropic; doc/theory.md, 'Joint compliance compensation'): the "
      "jointed body is not softened by the penalties, the cohesive law "
      "(peak traction, fracture energy) is unchanged, and the stable step "
      "does not change at penalties of 10 E and more. false: the triangles take E and nu as given and the "
      "joints soften the body by about x / (1 + x), x = 1.7 E / ((1 - nu) "
      "p_n) in plane stress (doc/tutorial/lesson-05-discrete-layer.md).");
    prm.declare_entry(
      "Anisotropic joint compliance compensation",
      "true",
      Patterns::Bool(),
      "With Joint compliance compensation: true removes each element's "
      "joints' compliance as the tensor it is (direction by direction), "
      "not only its isotropic average, so that an element whose joints are "
      "not spread evenly (on a free edge or face: no joint there; "
      "tetrahedra of a structured mesh) is as stiff as the material in "
      "every direction; the elements then take an anisotropic correction "
      "of Eq. 44 (doc/theory.md, 'Joint compliance compensation'; 6 values "
      "per triangle, 21 per tetrahedron). false: isotropic compensation "
      "only.");
    prm.declare_entry("Contact penalty factor",
                      "10",
                      Patterns::Double(0.),
                      "Normal contact penalty p_c = factor x E [Pa] of the "
                      "potential contact force (paper Eq. 5).");
    prm.declare_entry("Contact tangential penalty factor",
                      "1",
                      Patterns::Double(0.),
                      "Tangential (stick) contact penalty = factor x E [Pa] "
                      "per unit contact length fraction.");
    prm.declare_entry(
      "Contact force on the target",
      "potential gradient",
      Patterns::Selection("potential gradient|contact points"),
      "How the nodes of the target triangle get the normal contact force "
      "(doc/theory.md 5.5). potential gradient: minus the gradient of the "
      "contact energy p int (phi_c + phi_t) dA with respect to them, so "
      "that the normal force is conservative for any motion of the nodes, "
      "deformation included (no energy gained by vibrating pieces in "
      "contact). contact points: Munjiza's and the Y code's rule, the "
      "reaction of each contactor edge's force at its points, shared by the "
      "target's barycentric coordinates there; conservative for rigid "
      "motions only. Both give the same net force and moment per pair.");
    prm.declare_entry(
      "Contact of broken joint faces",
      "joint stiffness",
      Patterns::Selection("joint stiffness|contact penalty"),
      "The normal contact penalty between the two triangles of a broken "
      "joint (doc/theory.md 5.5). joint stiffness: the contact penalty "
      "scaled down, where the joint was softer in compression than the "
      "contact, so that the overlap of its faces stores no more energy than "
      "the joint stored for it: the contact takes over a compressed or "
      "hinged joint at its break without putting energy into the pieces. "
      "contact penalty: the same penalty as every other pair.");
    prm.declare_entry("Friction coefficient",
                      "0.5",
                      Patterns::Double(0.),
                      "Coulomb friction coefficient between broken faces "
                      "and bodies [-].");
    prm.declare_entry(
      "Friction memory slip",
      "1e-7",
      Patterns::Double(0.),
      "Memory slip L of the regularised Coulomb friction [m]: a contact's "
      "friction strength follows mu times its normal force, and the slip "
      "rate its rate effect compares with follows the slip rate, over this "
      "much slip (Prakash-Clifton; doc/theory.md 5.5, 'Regularised "
      "friction'). It removes the friction-excited vibration in which a "
      "block on an incline at a small margin mu - tan(theta) walks downhill "
      "(doc/cases/block_on_incline.md); a new contact slips a few L / "
      "(margin) before it sticks. Steady sliding and rest are Coulomb's. "
      "0: plain Coulomb friction, the strength mu N at every instant.");
    prm.declare_entry(
      "Friction rate effect",
      "0.01",
      Patterns::Double(0., 1.),
      "Rate effect a of the regularised friction [-]: the strength times "
      "1 + a ln((v0 + |v|) / (v0 + remembered slip rate)), stronger while "
      "the slip accelerates, Coulomb's in steady sliding (rate-and-state "
      "friction with equal direct and evolution effects; rocks: 0.005 to "
      "0.02). Unused with Friction memory slip = 0 (plain Coulomb).");
    prm.declare_entry("Friction reference slip rate",
                      "1e-6",
                      Patterns::Double(0.),
                      "Reference slip rate v0 of the rate effect [m/s] "
                      "(> 0).");
    prm.declare_entry("Softening law",
                      "Munjiza",
                      Patterns::Selection(
                        selection_of(discrete::softening_law_registry())),
                      "Post-peak softening of the joints: Munjiza's curve "
                      "or linear; both dissipate exactly G per unit area "
                      "in pure Mode I and II.");
    prm.declare_entry("Damping ratio",
                      "1",
                      Patterns::Double(0.),
                      "Modal damping ratio of each element's highest "
                      "free mode [-]: the viscosity eta of the viscous "
                      "stress 2 eta sym(grad v) is chosen per element so "
                      "that 1 damps that mode critically; a mode of "
                      "frequency omega gets about ratio x omega / "
                      "omega_max. 0: undamped (doc/theory.md 5.3).");
    prm.declare_entry("Mass damping",
                      "0",
                      Patterns::Double(0.),
                      "Mass-proportional damping c of a force -c m v on "
                      "every free node [1/s]: damps the low modes, for "
                      "quasi-static loading (dynamic relaxation; about "
                      "2 pi c_p / L for the lowest mode of a body of size "
                      "L); 0: none. Counted with the viscous dissipation.");
    prm.declare_entry(
      "Mass scaling factor",
      "1",
      Patterns::Double(1.),
      "Mass scaling f >= 1: every node's mass is f times rho A / 3 [-]. The "
      "mechanics then runs sqrt(f) times slower in physical time with a "
      "sqrt(f) times longer stable step (the Damping ratio is kept, Mass "
      "damping acts on the scaled mass); gravity keeps the physical weight "
      "and the heat its capacity rho c. For a dynamic run under a load that "
      "is slow against the body's wave transit (a heating or a quench over "
      "many milliseconds): valid while sqrt(f) x the lowest period stays "
      "well below the load's time scale; check it with a second, smaller f "
      "(doc/theory.md 5.6). 1: the physical inertia.");
    prm.declare_entry("Gravity",
                      "0, 0",
                      Patterns::List(Patterns::Double(), 2, 3, ","),
                      "Gravitational acceleration [m/s^2]: g_x, g_y with "
                      "Mesh/Dimension = 2, g_x, g_y, g_z with Mesh/Dimension "
                      "= 3 (there the default 0, 0 means no gravity).");
    prm.declare_entry(
      "Gravity ramp time",
      "0",
      Patterns::Double(0.),
      "Gravity grows linearly from zero to Gravity over this time from "
      "t = 0 [s]: bodies that start at rest on their supports are loaded "
      "gradually instead of being dropped onto their contact springs at "
      "once (which sets them bouncing; doc/cases/block_on_incline.md). "
      "0: full gravity from the first step. Dynamic runs only (discrete "
      "mechanics, multi-rate thermo-mechanics).");
    prm.declare_entry("Contact buffer",
                      "0",
                      Patterns::Double(0.),
                      "Broad-phase buffer [m]: contact candidates are "
                      "searched again once nodes have moved half of it; "
                      "0: a quarter of the smallest element size.");
    prm.declare_entry("Contact",
                      "true",
                      Patterns::Bool(),
                      "Contact between free faces (boundary edges and "
                      "broken joints); false: no contact at all.");
    prm.declare_entry("Initial cracks",
                      "",
                      Patterns::Anything(),
                      "Pre-existing fractures: segments 'x0, y0, x1, y1' [m] "
                      "separated by ';'. Every joint lying on a segment "
                      "starts broken (it conducts no heat and carries no "
                      "cohesion; its faces contact). The mesh must have "
                      "edges along the segments (gmsh: Line In Surface).");
    prm.declare_entry("Threads",
                      "0",
                      Patterns::Integer(0, 1024),
                      "Threads of the discrete layer (explicit loop, joint "
                      "and contact forces, contact search, discrete heat) "
                      "[-]; 0: all cores this process may use (its affinity "
                      "mask, the node's cores shared among the MPI ranks on "
                      "the node). More than that is capped to it unless "
                      "Allow oversubscription is true. Results do not "
                      "depend on it.");
    prm.declare_entry(
      "Vector instructions",
      "auto",
      Patterns::Selection(
        "auto|" + selection_of(discrete::vector_instructions_registry())),
      "Instruction set of the explicit loop, which takes the triangles whose "
      "nodes are all free and the joints on the rising branch of their law "
      "(in 3D the tetrahedra whose nodes are all free and the intact face "
      "joints) as many at a time as one register holds doubles, one per "
      "lane (node_update.cc, joints.cc, tetrahedral_update.cc): auto: the "
      "widest this processor has, but AVX2 instead of AVX-512 where a "
      "process has more than 65 536 triangles, and in 3D (there the loop "
      "waits on memory and AVX2 was faster, doc/performance.md); "
      "AVX-512 (8), AVX2 (4), SSE2 (2, every "
      "x86-64 processor); none: one at a time. Every lane does "
      "the operations of the one-at-a-time loop in the same order, so "
      "results are bitwise the same with every choice; a set this processor "
      "lacks is an error.");
    prm.declare_entry(
      "Triangle numbering",
      "Hilbert curve",
      Patterns::Selection("Hilbert curve|mesh"),
      "Order in which the discrete layer numbers its triangles (tetrahedra "
      "in 3D): Hilbert curve (along a Hilbert curve through the centroids, "
      "so that each MPI rank, which owns a range of triangles, owns a "
      "compact region with a small halo, and neighbours lie near in memory) "
      "or mesh (the order of the mesh file or generator, after global "
      "refinement). Changes results "
      "only at round-off (sums in another order); the random joint "
      "strengths (Heterogeneity) and the monitors' elements do not depend "
      "on it.");
    prm.declare_entry("Allow oversubscription",
                      "false",
                      Patterns::Bool(),
                      "true: run Threads threads even where they exceed "
                      "the cores this process may use (threads then share "
                      "cores; slower); false: cap Threads at those cores.");
    prm.declare_entry("Heterogeneity",
                      "none",
                      Patterns::Selection("none|Weibull|normal"),
                      "Per-joint random tensile strength and cohesion: none, "
                      "Weibull (mean = material value, modulus below) or "
                      "normal (mean = material value, coefficient of "
                      "variation below, truncated at 1 % of the mean).");
    prm.declare_entry("Weibull modulus",
                      "10",
                      Patterns::Double(0.1),
                      "Weibull modulus m of the joint strengths [-].");
    prm.declare_entry("Coefficient of variation",
                      "0.1",
                      Patterns::Double(0.),
                      "Standard deviation / mean of normal joint strengths "
                      "[-].");
    prm.declare_entry(
      "Expansion heterogeneity",
      "none",
      Patterns::Selection("none|normal"),
      "Per-triangle random thermal expansion coefficient, the grain-scale "
      "mismatch of a rock made of several minerals (in granite quartz "
      "expands about twice as much as feldspar): none, or normal (mean = "
      "the material's coefficient, standard deviation = Expansion "
      "coefficient of variation times the mean, truncated at 0). Each "
      "triangle is one grain: under a uniform temperature change the "
      "triangles then load each other and their joints, and these "
      "mismatch stresses stay where a crack has cut the body. The field "
      "(heterogeneity.h) is drawn from Random seed in the mesh's order of "
      "the triangles: independent of Triangle numbering and of the joint "
      "strengths' field.");
    prm.declare_entry("Expansion coefficient of variation",
                      "0.3",
                      Patterns::Double(0.),
                      "Standard deviation / mean of the triangles' thermal "
                      "expansion coefficients (Expansion heterogeneity = "
                      "normal) [-].");
    prm.declare_entry("Random seed",
                      "1",
                      Patterns::Integer(0),
                      "Seed of the random fields: the joint strengths "
                      "(Heterogeneity) and the expansion coefficients "
                      "(Expansion heterogeneity), each from its own "
                      "sequence.");
    prm.declare_entry("Maximum steps",
                      "0",
                      Patterns::Integer(0),
                      "Stop after this many explicit steps even before End "
                      "time; 0: no limit.");
    prm.leave_subsection();
  }

  void
  DiscreteMechanicsParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Discrete mechanics");
    time_step                   = prm.get_double("Time step");
    safety_factor               = prm.get_double("Safety factor");
    joint_normal_penalty_factor = prm.get_double("Joint normal penalty factor");
    joint_tangential_penalty_factor =
      prm.get_double("Joint tangential penalty factor");
    joint_compliance_compensation =
      prm.get_bool("Joint compliance compensation");
    anisotropic_joint_compliance_compensation =
      prm.get_bool("Anisotropic joint compliance compensation");
    contact_penalty_factor = prm.get_double("Contact penalty factor");
    contact_tangential_penalty_factor =
      prm.get_double("Contact tangential penalty factor");
    friction_coefficient = prm.get_double("Friction coefficient");
    friction_memory_slip = prm.get_double("Friction memory slip");
    friction_rate_effect = prm.get_double("Friction rate effect");
    friction_reference_slip_rate =
      prm.get_double("Friction reference slip rate");
    if (!(friction_reference_slip_rate > 0.))
      throw InputError("Discrete mechanics/Friction reference slip rate must "
                       "be > 0 [m/s].");
    contact_broken_faces_at_joint_stiffness =
      prm.get("Contact of broken joint faces") == "joint stiffness";
    contact_potential_gradient_on_target =
      prm.get("Contact force on the target") == "potential gradient";
    {
      const std::string name = prm.get("Softening law");
      for (const auto &[entry, law] : discrete::softening_law_registry())
        if (entry == name)
          softening_law = law;
    }
    damping_ratio       = prm.get_double("Damping ratio");
    mass_damping        = prm.get_double("Mass damping");
    mass_scaling_factor = prm.get_double("Mass scaling factor");
    gravity             = Utilities::string_to_double(
      Utilities::split_string_list(prm.get("Gravity"), ','));
    gravity_ramp_time      = prm.get_double("Gravity ramp time");
    contact_buffer         = prm.get_double("Contact buffer");
    contact                = prm.get_bool("Contact");
    threads                = prm.get_integer("Threads");
    allow_oversubscription = prm.get_bool("Allow oversubscription");
    vector_instructions =
      discrete::resolve_vector_instructions(prm.get("Vector instructions"));
    vector_instructions_auto = prm.get("Vector instructions") == "auto";
    hilbert_curve_numbering  = prm.get("Triangle numbering") == "Hilbert curve";
    {
      const std::string name = prm.get("Heterogeneity");
      heterogeneity          = name == "Weibull" ? Heterogeneity::weibull :
                               name == "normal"  ? Heterogeneity::normal :
                                                   Heterogeneity::none;
    }
    weibull_modulus          = prm.get_double("Weibull modulus");
    coefficient_of_variation = prm.get_double("Coefficient of variation");
    expansion_heterogeneity  = prm.get("Expansion heterogeneity") == "normal" ?
                                 ExpansionHeterogeneity::normal :
                                 ExpansionHeterogeneity::none;
    expansion_coefficient_of_variation =
      prm.get_double("Expansion coefficient of variation");
    random_seed = prm.get_integer("Random seed");
    max_steps   = prm.get_integer("Maximum steps");
    initial_cracks.clear();
    for (const auto &text :
         Utilities::split_string_list(prm.get("Initial cracks"), ';'))
      {
        const auto            values = Utilities::split_string_list(text, ',');
        std::array<double, 4> segment;
        bool                  valid = values.size() == 4;
        for (unsigned int i = 0; valid && i < 4; ++i)
          {
            try
              {
                segment[i] = Utilities::string_to_double(values[i]);
                valid      = std::isfinite(segment[i]);
              }
            catch (...)
              {
                valid = false;
              }
          }
        if (!valid)
          throw InputError("Discrete mechanics/Initial cracks: '" + text +
                           "' is not a segment; allowed are 'x0, y0, x1, y1' "
                           "[m], segments separated by ';'.");
        initial_cracks.push_back(segment);
      }
    prm.leave_subsection();
    require_positive(joint_normal_penalty_factor,
                     "Joint normal penalty factor");
    require_positive(joint_tangential_penalty_factor,
                     "Joint tangential penalty factor");
    require_positive(contact_penalty_factor, "Contact penalty factor");
    require_positive(contact_tangential_penalty_factor,
                     "Contact tangential penalty factor");
  }

  void
  DiscreteHeatParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Discrete heat");
    std::string source_names;
    for (const auto &name : discrete::temperature_source_names())
      source_names += (source_names.empty() ? "" : "|") + name;
    prm.declare_entry(
      "Temperature source",
      "discrete heat",
      Patterns::Selection(source_names),
      "discrete thermo-mechanics: where the nodal temperatures that load the "
      "triangles come from. " +
        discrete::temperature_source_descriptions() +
        "The continuum source solves on the unbroken reference mesh: it does "
        "not see cracks or contacts (see Continuum source at broken "
        "joints).");
    prm.declare_entry(
      "Continuum source at broken joints",
      "stop",
      Patterns::Selection("stop|accept"),
      "Temperature source = continuum heat conducts across every joint as if "
      "intact and exchanges no contact heat. stop: the run stops (exit 2, "
      "outputs so far and a checkpoint kept) at the first thermal step "
      "after a joint breaks, where the temperature would start to be wrong "
      "near the crack; accept: it goes on, warns once on stderr and "
      "summary.json records continuum_heat_across_cracks = true.");
    prm.declare_entry("Time integration",
                      "implicit",
                      Patterns::Selection("implicit|explicit"),
                      "implicit: backward Euler (paper Eq. 22) with the "
                      "capacity matrix of Capacity matrix, joint exchange in "
                      "the matrix, CG; explicit: forward Euler with the lumped "
                      "capacity, the step limited to Safety factor x the "
                      "stable step (a larger Time stepping/Time step is "
                      "refused).");
    prm.declare_entry(
      "Capacity matrix",
      "consistent",
      Patterns::Selection("consistent|lumped"),
      "The capacity matrix of the implicit step (doc/theory.md 2.3). "
      "consistent: M_ab = rho c V (1 + delta_ab) / ((dim + 1)(dim + 2)), "
      "the smaller error of a smooth field; with steps much shorter than "
      "h^2 / kappa a steep front (a quench) makes temperatures overshoot "
      "their initial and boundary values by a few percent of the jump "
      "next to it. lumped: rho c V / (dim + 1) on each node, no such "
      "overshoot where no element is obtuse. Explicit steps always use "
      "the lumped capacity.");
    prm.declare_entry(
      "Conduction matrix",
      "consistent",
      Patterns::Selection("consistent|M-matrix"),
      "The conduction matrix of each element (doc/theory.md 7.7). "
      "consistent: K_ab = k V grad N_a . grad N_b, the P1 Galerkin matrix. "
      "M-matrix: its positive couplings (two nodes whose opposite faces "
      "meet at an obtuse angle, common in gmsh's tetrahedra) moved onto the "
      "diagonal, which conserves heat and adds conduction along those "
      "edges: with Capacity matrix = lumped an implicit step then keeps "
      "every temperature between the extremes of the old temperatures and "
      "the boundary values (no overshoot at a quench front), at the price "
      "of a first-order error on obtuse elements. Used by the implicit and "
      "the explicit steps.");
    prm.declare_entry("Joint conductance factor",
                      "1000",
                      Patterns::Double(0.),
                      "beta in the joint heat-transfer coefficient "
                      "k_i = beta k / h [W/(m^2 K)] of intact joints (paper "
                      "Eqs. 25-27; k the harmonic mean conductivity of the "
                      "two triangles, h the joint length) [-]. Large beta "
                      "gives the continuum; the difference falls like "
                      "1/beta.");
    prm.declare_entry("Contact conductance",
                      "1e4",
                      Patterns::Double(0.),
                      "h_c of the heat exchanged over contact overlaps "
                      "[W/(m^2 K)]; see Contact heat model.");
    {
      std::string names;
      for (const auto &[name, model] : discrete::contact_heat_model_registry())
        names += (names.empty() ? "" : "|") + std::string(name);
      prm.declare_entry(
        "Contact heat model",
        discrete::contact_heat_model_registry()[0].first,
        Patterns::Selection(names),
        "Driving term of the heat exchanged by a contact pair, distributed "
        "to the nodes of both triangles with the area coordinates of the "
        "overlap's centroid G (paper Eqs. 34-36). temperature difference: "
        "Q = h_c L_c (T_target(G) - T_contactor(G)) [W/m], L_c the chord of "
        "the interpenetration; two bodies at different temperatures "
        "exchange heat at the rate the contact conductance h_c says. paper "
        "literal: the paper's Eqs. 29-33 as printed, for reproducing the "
        "paper, Q = h_c A (grad T_contactor + grad T_target) . n [W/m] into "
        "the contactor (A the overlap area, n the unit vector from the "
        "contactor's centroid to the target's, k_ij = 1 in Eq. 29 so that "
        "Q is a heat); it is driven by temperature GRADIENTS only, so two "
        "isothermal bodies at different temperatures exchange exactly "
        "nothing (the paper's flaw, doc/theory.md); in implicit time "
        "integration it is taken at the start of the step (explicitly).");
    }
    prm.declare_entry("Safety factor",
                      "0.9",
                      Patterns::Double(1e-6, 1.),
                      "Explicit: fraction of the stable thermal step used "
                      "when Time stepping/Time step is larger [-].");
    prm.declare_entry("Linear solver tolerance",
                      "1e-12",
                      Patterns::Double(1e-16, 1e-2),
                      "Implicit: CG stops at this residual relative to the "
                      "right-hand side [-].");
    prm.declare_entry(
      "Preconditioner",
      "jacobi",
      Patterns::Selection("jacobi|amg"),
      "Implicit: the preconditioner of the conjugate gradients. jacobi: "
      "the diagonal of each row; every sum is taken in a fixed order, so "
      "the temperatures are bitwise the same on any number of MPI ranks and "
      "threads. amg: algebraic multigrid (Trilinos ML) on the distributed "
      "matrix; far fewer iterations on large meshes and long steps, but the "
      "hierarchy depends on the ranks, so results on different rank counts "
      "agree to the Linear solver tolerance only. The matrix and its "
      "hierarchy are built again only when the matrix changes (a new "
      "step size, contacts, broken joints; summary.json amg_setups).");
    prm.declare_entry("Mechanical steps per thermal step",
                      "0",
                      Patterns::Integer(0),
                      "Multi-rate coupling: one thermal step every n "
                      "mechanical steps; 0: the largest n that keeps the "
                      "thermal step stable (explicit) or 1000 (implicit).");
    prm.declare_entry(
      "Coupling",
      "dynamic",
      Patterns::Selection("dynamic|quasi-static"),
      "discrete thermo-mechanics: dynamic: one physical clock, a thermal step "
      "every n mechanical steps (thermal shock, fast events); quasi-static: "
      "slow heating or cooling, each thermal step of Time stepping/Time step "
      "is followed by up to Mechanical steps per thermal step damped "
      "mechanical steps (no physical time) until kinetic / strain energy < "
      "Relaxation tolerance; imposed velocities and displacements follow the "
      "thermal time (their motion over a thermal step is spread over the "
      "first 100 relaxation steps); outputs in thermal (physical) time.");
    prm.declare_entry("Relaxation tolerance",
                      "1e-6",
                      Patterns::Double(0.),
                      "Quasi-static coupling: relaxation stops when the "
                      "kinetic energy falls below this fraction of the "
                      "strain energy [-] (checked every 50 steps).");
    prm.declare_entry("Relaxation force tolerance",
                      "1e-3",
                      Patterns::Double(0.),
                      "Quasi-static coupling: relaxation also requires the "
                      "out-of-balance force (net static force on the free "
                      "node components) below this fraction of the "
                      "internal element forces (both as Euclidean norms "
                      "over the nodes) [-].");
    prm.declare_entry(
      "Relaxation predictor",
      "none",
      Patterns::Selection("none|extrapolate"),
      "Quasi-static coupling: where each relaxation starts [-]. none: at the "
      "state the last relaxation ended in; extrapolate: that state plus the "
      "displacement increment of the last relaxation, scaled by the ratio of "
      "the new to the last thermal step (free node components only; not "
      "after a relaxation in which joints were damaged or broke), so that a "
      "response linear in time needs almost no relaxation: for slow, steady "
      "heating or loading (doc/theory.md 8).");
    prm.declare_entry(
      "Relaxation damping",
      "mass",
      Patterns::Selection("mass|kinetic"),
      "Quasi-static coupling: how a relaxation is damped [-]. mass: by "
      "Discrete mechanics/Mass damping (and the element viscosity) alone; "
      "kinetic: besides, the velocities of the free nodes are set to zero "
      "whenever the kinetic energy has passed a peak (kinetic damping: the "
      "dominant mode is then near its equilibrium), which needs no tuning to "
      "the lowest frequency and suits bodies whose lowest mode changes as "
      "they crack (Mass damping 0 or small); convergence is then judged on "
      "the largest kinetic energy since the last check (doc/theory.md 8).");
    prm.declare_entry(
      "Fracture event duration",
      "0",
      Patterns::Double(0.),
      "Quasi-static coupling with Relaxation damping = kinetic: once a joint "
      "breaks in a relaxation, the velocity resets pause for this much time "
      "of mechanical steps (duration / mechanical time step, counted again "
      "from every later break), so that the fracture event runs as it does "
      "in the body: cracks grow and the released energy spreads with the "
      "inertia and the material's own damping (element viscosity, Mass "
      "damping), not along the path of the kinetic damping; then the "
      "relaxation settles as before. A few times the time a wave takes "
      "across the body. The steps count against Mechanical steps per "
      "thermal step. 0: kinetic damping throughout [s].");
    prm.declare_entry("Relaxation cap is error",
                      "false",
                      Patterns::Bool(),
                      "Quasi-static coupling: a relaxation that reaches "
                      "Mechanical steps per thermal step without reaching "
                      "Relaxation tolerance stops the run (exit 2, results "
                      "kept) instead of a warning; summary.json counts "
                      "such steps as relaxations_at_cap either way.");
    prm.declare_entry(
      "Thermal step growth factor",
      "1",
      Patterns::Double(1., 10.),
      "Quasi-static coupling: thermal step n is Time stepping/Time step x "
      "factor^n, capped at Maximum thermal step; > 1 for a quench or a "
      "sudden heating, whose early steps must be short and whose late "
      "steps may be long [-].");
    prm.declare_entry(
      "Maximum utilisation change",
      "0.01",
      Patterns::Double(0., 1.),
      "Quasi-static coupling: the thermal step shrinks so that the strength "
      "utilisation U of no undamaged joint (opening / peak opening or slip "
      "/ peak slip, 1 at the peak) is predicted, from its rate over the "
      "last thermal step, to rise by more than this much per step (or, far "
      "from the peak, by more than Utilisation margin fraction x (1 - U)), "
      "and once the highest U exceeds 1 - 10 x this value the step is at "
      "most this fraction of the elapsed time: the time of first damage is "
      "resolved to about this fraction whatever Time step and growth "
      "factor say [-]. 0: off.");
    prm.declare_entry(
      "Utilisation margin fraction",
      "0",
      Patterns::Double(0., 1.),
      "Quasi-static coupling: once a joint of the model is damaged, a joint "
      "whose strength utilisation U is far from its peak may rise per "
      "thermal step by this fraction of its margin 1 - U where that is more "
      "than Maximum utilisation change: the step control then follows each "
      "joint's approach to its strength (about 31 steps from U = 0 to 0.99 "
      "at 0.1) instead of holding every step to the change of the fastest "
      "joint, and the small ups and downs of joints far from their strength "
      "between relaxations do not hold the step short. Before the first "
      "damage Maximum utilisation change alone sets the steps, so that the "
      "time of first damage does not depend on this entry. Set 0.1 where contact and friction act between "
      "crack faces (their relaxations end a little differently each time: "
      "with 0 the 3D quenched disc's step stays at Minimum thermal step "
      "once its cracks open) [-]. 0: every joint by Maximum utilisation "
      "change alone.");
    prm.declare_entry(
      "Maximum broken joints per step",
      "2",
      Patterns::Integer(0, 1000000),
      "Quasi-static coupling: thermal step control through the fracture "
      "process. Counted per thermal step are the joints that break; where "
      "more broke than this, the next step is shorter by this number over "
      "theirs, and a step in which more than twice this many broke, or in "
      "which damage grew and whose relaxation reached Mechanical steps per "
      "thermal step, is re-run from its start with a shorter step, down to "
      "Minimum thermal step, where it "
      "is accepted as unstable crack growth (summary.json "
      "rejected_thermal_steps, unstable_thermal_steps). After a shortened "
      "step the step grows back by at most a factor 2 per step. The onset "
      "of damage is resolved by Maximum utilisation change [-]. 0: off (no "
      "re-runs).");
    prm.declare_entry(
      "Minimum thermal step",
      "0",
      Patterns::Double(0.),
      "Quasi-static coupling: the shortest thermal step of the utilisation "
      "and damage controls; crack growth that a step this short does not "
      "resolve runs as one event at that load (with inertia where Fracture "
      "event duration > 0). 0: 1e-3 x Time stepping/Time step [s].");
    prm.declare_entry("Maximum thermal step",
                      "0",
                      Patterns::Double(0.),
                      "Quasi-static coupling: cap of the growing thermal "
                      "step; 0: no cap [s].");
    prm.leave_subsection();
  }

  void
  DiscreteHeatParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Discrete heat");
    temperature_source = prm.get("Temperature source");
    accept_continuum_source_at_broken_joints =
      prm.get("Continuum source at broken joints") == "accept";
    time_integration         = prm.get("Time integration") == "explicit" ?
                                 TimeIntegration::explicit_euler :
                                 TimeIntegration::implicit;
    lumped_implicit_capacity = prm.get("Capacity matrix") == "lumped";
    conduction_m_matrix      = prm.get("Conduction matrix") == "M-matrix";
    joint_conductance_factor = prm.get_double("Joint conductance factor");
    contact_conductance      = prm.get_double("Contact conductance");
    safety_factor            = prm.get_double("Safety factor");
    solver_tolerance         = prm.get_double("Linear solver tolerance");
    preconditioner           = prm.get("Preconditioner") == "amg" ?
                                 Preconditioner::amg :
                                 Preconditioner::jacobi;
    mechanical_steps_per_thermal_step =
      prm.get_integer("Mechanical steps per thermal step");
    coupling = prm.get("Coupling") == "quasi-static" ? Coupling::quasi_static :
                                                       Coupling::dynamic;
    relaxation_tolerance       = prm.get_double("Relaxation tolerance");
    relaxation_cap_is_error    = prm.get_bool("Relaxation cap is error");
    relaxation_force_tolerance = prm.get_double("Relaxation force tolerance");
    relaxation_predictor    = prm.get("Relaxation predictor") == "extrapolate" ?
                                RelaxationPredictor::extrapolate :
                                RelaxationPredictor::none;
    relaxation_damping      = prm.get("Relaxation damping") == "kinetic" ?
                                RelaxationDamping::kinetic :
                                RelaxationDamping::mass;
    fracture_event_duration = prm.get_double("Fracture event duration");
    thermal_step_growth     = prm.get_double("Thermal step growth factor");
    maximum_thermal_step    = prm.get_double("Maximum thermal step");
    maximum_utilisation_change  = prm.get_double("Maximum utilisation change");
    utilisation_margin_fraction = prm.get_double("Utilisation margin fraction");
    maximum_broken_joints_per_step =
      prm.get_integer("Maximum broken joints per step");
    minimum_thermal_step = prm.get_double("Minimum thermal step");
    {
      const std::string name  = prm.get("Contact heat model");
      bool              found = false;
      for (const auto &[entry, model] : discrete::contact_heat_model_registry())
        if (name == entry)
          {
            contact_heat_model = model;
            found              = true;
          }
      if (!found) // the Selection pattern has already refused it
        throw InputError("Discrete heat/Contact heat model = '" + name +
                         "': unknown.");
    }
    prm.leave_subsection();
    if (thermal_step_growth > 1. && coupling != Coupling::quasi_static)
      throw InputError(
        "Discrete heat/Thermal step growth factor = " +
        Utilities::to_string(thermal_step_growth) +
        ": a growing thermal step needs Coupling = quasi-static (the dynamic "
        "coupling ties the thermal step to the mechanical one); allowed is 1.");
    if (fracture_event_duration > 0. &&
        (coupling != Coupling::quasi_static ||
         relaxation_damping != RelaxationDamping::kinetic))
      throw InputError(
        "Discrete heat/Fracture event duration = " +
        Utilities::to_string(fracture_event_duration) +
        ": pauses the kinetic damping of a quasi-static relaxation, so it "
        "needs Coupling = quasi-static and Relaxation damping = kinetic "
        "(the dynamic coupling runs every fracture with inertia anyway); "
        "allowed otherwise is 0.");
    if (!(joint_conductance_factor > 0.))
      throw InputError("Discrete heat/Joint conductance factor = " +
                       Utilities::to_string(joint_conductance_factor) +
                       ": must be > 0 (intact joints must conduct).");
  }

  void
  DiscreteBodyParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Discrete bodies");
    for (unsigned int n = 1; n <= max_bodies; ++n)
      {
        prm.enter_subsection("Body " + std::to_string(n));
        prm.declare_entry(
          "Material ids",
          "",
          Patterns::List(Patterns::Integer(0, 255), 0, 256, ","),
          "Cells of these material ids form the body (empty: "
          "unused). Material ids named by no body move "
          "freely.");
        prm.declare_entry("Motion",
                          "free",
                          Patterns::Selection("free|fixed|velocity"),
                          "free: moves under its forces; fixed: never "
                          "moves (walls, supports); velocity: every node "
                          "moves with the prescribed velocity below "
                          "(platens).");
        prm.declare_entry("Velocity x",
                          "0",
                          Patterns::Anything(),
                          "Prescribed velocity v_x(t) for Motion = velocity, "
                          "function of t [m/s].");
        prm.declare_entry("Velocity y",
                          "0",
                          Patterns::Anything(),
                          "Prescribed velocity v_y(t) for Motion = velocity, "
                          "function of t [m/s].");
        prm.declare_entry("Initial velocity x",
                          "0",
                          Patterns::Anything(),
                          "Initial velocity v_x(x, y) of a free body [m/s].");
        prm.declare_entry("Initial velocity y",
                          "0",
                          Patterns::Anything(),
                          "Initial velocity v_y(x, y) of a free body [m/s].");
        prm.declare_entry("Velocity z",
                          "0",
                          Patterns::Anything(),
                          "Mesh/Dimension = 3: prescribed velocity v_z(t) for "
                          "Motion = velocity, function of t [m/s].");
        prm.declare_entry("Initial velocity z",
                          "0",
                          Patterns::Anything(),
                          "Mesh/Dimension = 3: initial velocity v_z(x, y, z) "
                          "of a free body [m/s].");
        prm.declare_entry(
          "Initial temperature",
          "",
          Patterns::Anything(),
          "Initial temperature of the cells of this body's Material ids, "
          "function of x, y [m] (t = start time) [C]; empty: each material's "
          "Materials/Material <id>/Initial temperature, else Initial "
          "conditions/Temperature. Precedence: body > material > global; "
          "setting it here and for one of the body's materials is refused. "
          "Honoured by the continuum heat solver too (a body is a set of "
          "material ids).");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }

  void
  DiscreteBodyParameters::parse_parameters(ParameterHandler &prm)
  {
    bodies.clear();
    std::set<types::material_id> used;
    prm.enter_subsection("Discrete bodies");
    for (unsigned int n = 1; n <= max_bodies; ++n)
      {
        DiscreteBody body;
        body.name   = "Discrete bodies/Body " + std::to_string(n);
        body.number = n;
        prm.enter_subsection("Body " + std::to_string(n));
        for (const int id : Utilities::string_to_int(
               Utilities::split_string_list(prm.get("Material ids"), ',')))
          body.material_ids.push_back(static_cast<types::material_id>(id));
        const std::string motion = prm.get("Motion");
        body.motion     = motion == "fixed"    ? DiscreteBody::Motion::fixed :
                          motion == "velocity" ? DiscreteBody::Motion::velocity :
                                                 DiscreteBody::Motion::free;
        body.velocity_x = prm.get("Velocity x");
        body.velocity_y = prm.get("Velocity y");
        body.initial_velocity_x = prm.get("Initial velocity x");
        body.initial_velocity_y = prm.get("Initial velocity y");
        body.velocity_z         = prm.get("Velocity z");
        body.initial_velocity_z = prm.get("Initial velocity z");
        body.initial_temperature =
          Utilities::trim(prm.get("Initial temperature"));
        prm.leave_subsection();
        for (const auto id : body.material_ids)
          if (!used.insert(id).second)
            throw InputError(body.name + "/Material ids: material id " +
                             std::to_string(id) +
                             " already belongs to another body.");
        if (body.material_ids.empty() && !body.initial_temperature.empty())
          throw InputError(body.name + "/Initial temperature = '" +
                           body.initial_temperature + "' is set but " +
                           body.name +
                           "/Material ids is empty: name the material ids of "
                           "the body, or leave Initial temperature empty.");
        if (!body.material_ids.empty())
          bodies.push_back(body);
      }
    prm.leave_subsection();
  }

  std::string
  DiscreteHeatParameters::coupling_name() const
  {
    return coupling == Coupling::quasi_static ? "quasi-static" : "dynamic";
  }

  std::string
  DiscreteHeatParameters::time_integration_name() const
  {
    return time_integration == TimeIntegration::explicit_euler ? "explicit" :
                                                                 "implicit";
  }

  void
  DiscreteBodyParameters::complete(Parameters &parameters) const
  {
    const auto &materials = parameters.materials.materials;
    // a body and one of its materials may not both set the initial
    // temperature: two entries for the same cells
    for (const auto &body : bodies)
      if (!body.initial_temperature.empty())
        for (const auto id : body.material_ids)
          if (id < MaterialParameters::max_materials &&
              !materials[id].initial_temperature.empty())
            throw InputError(
              body.name + "/Initial temperature = '" +
              body.initial_temperature + "' and Materials/Material " +
              std::to_string(id) + "/Initial temperature = '" +
              materials[id].initial_temperature +
              "' both set the initial temperature of material " +
              std::to_string(id) + " (" + body.name +
              "/Material ids); allowed is one of them: leave the other "
              "empty.");
    // malformed expressions are refused here, naming the entry, whichever
    // layer runs and whether or not the mesh has that material
    for (const auto &body : bodies)
      if (!body.initial_temperature.empty())
        {
          make_expression_function(body.initial_temperature,
                                   body.name + "/Initial temperature");
          parameters.initial_temperature_overrides.push_back(
            {body.material_ids,
             {body.initial_temperature, body.name + "/Initial temperature"}});
        }
  }
} // namespace tmfdem
