/**
 * @file
 * The prm subsections of how a run goes: Time stepping, Adaptive
 * refinement, Heat solver, Mechanics, Output, Monitors, Checkpoint, Guards.
 */
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>

#include "parameter_helpers.h"

namespace tmfdem
{
  using parameter_helpers::parse_point;
  using parameter_helpers::parse_space_point;
  using parameter_helpers::point_pattern;
  using parameter_helpers::selection_of;
  using parameter_helpers::space_point_pattern;

  // --------------------------------------------------------- Time stepping
  void
  TimeSteppingParameters::declare_parameters(ParameterHandler &prm)
  {
    std::vector<std::string> methods;
    for (const auto &method : theta_scheme_registry())
      methods.push_back(method.first);
    prm.enter_subsection("Time stepping");
    prm.declare_entry("Mode",
                      "transient",
                      Patterns::Selection("transient|steady"),
                      "transient: march from Start time to End time; steady: "
                      "solve the stationary problem directly.");
    prm.declare_entry("Method",
                      "backward Euler",
                      Patterns::Selection(selection_of(methods)),
                      "One-step theta method: backward Euler (theta = 1, "
                      "first order, L-stable) or Crank-Nicolson (theta = 1/2, "
                      "second order).");
    prm.declare_entry(
      "Rannacher steps",
      "4",
      Patterns::Integer(0),
      "Crank-Nicolson only: the run starts with this many backward Euler "
      "half steps (Rannacher smoothing), which damp the high-frequency error "
      "of non-smooth data (a Dirichlet value that differs from the initial "
      "temperature) that Crank-Nicolson alone would carry undamped; 0 starts "
      "with Crank-Nicolson.");
    prm.declare_entry("Start time", "0", Patterns::Double(), "Start time [s].");
    prm.declare_entry("End time", "1", Patterns::Double(), "End time [s].");
    prm.declare_entry("Time step",
                      "0.1",
                      Patterns::Double(0.),
                      "Time step [s], > 0; shortened to land on output "
                      "times.");
    prm.leave_subsection();
  }

  void
  TimeSteppingParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    mode   = prm.get("Mode") == "steady" ? Mode::steady : Mode::transient;
    method = prm.get("Method");
    rannacher_steps = prm.get_integer("Rannacher steps");
    start_time      = prm.get_double("Start time");
    end_time        = prm.get_double("End time");
    time_step       = prm.get_double("Time step");
    prm.leave_subsection();
    for (const auto &[name, value] : theta_scheme_registry())
      if (name == method)
        theta = value;
    if (mode == Mode::transient)
      {
        if (!(time_step > 0.))
          throw InputError(
            "Time stepping/Time step = " + Utilities::to_string(time_step) +
            ": must be > 0 [s].");
        if (!(end_time > start_time))
          throw InputError(
            "Time stepping/End time = " + Utilities::to_string(end_time) +
            ": must be later than Start time = " +
            Utilities::to_string(start_time) + " [s].");
        // the models stop within 1e-10 max(1, |End time|) of End time
        // (OutputSchedule::default_tolerance()): a shorter span runs none
        if (end_time - start_time <= 1e-10 * std::max(1., std::abs(end_time)))
          throw InputError(
            "Time stepping/End time = " + Utilities::to_string(end_time) +
            " s lies within round-off (1e-10 max(1, |End time|)) of Start "
            "time = " +
            Utilities::to_string(start_time) +
            " s: no step would be computed. Allowed is an End time later "
            "than Start time by at least one time step.");
        if ((end_time - start_time) / time_step > 1e9)
          throw InputError("Time stepping: (End time - Start time) / Time step "
                           "exceeds 1e9 steps.");
      }
  }

  // --------------------------------------------------- Adaptive refinement
  void
  AdaptivityParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Adaptive refinement");
    prm.declare_entry("Enable",
                      "false",
                      Patterns::Bool(),
                      "Adapt the mesh with the Kelly error estimator. "
                      "Quadrilateral meshes only (deal.II 9.4.1 cannot "
                      "coarsen triangles, and Kelly fails on triangle meshes "
                      "with hanging nodes).");
    prm.declare_entry("Strategy",
                      "fixed fraction",
                      Patterns::Selection("fixed fraction|fixed number"),
                      "fixed fraction: refine the cells that carry Refine "
                      "fraction of the estimated error (cells of equal error "
                      "are treated alike, which symmetric problems need); "
                      "fixed number: refine Refine fraction of the cells.");
    prm.declare_entry("Interval",
                      "5",
                      Patterns::Integer(1),
                      "Transient runs: adapt every this many steps [-].");
    prm.declare_entry("Refine fraction",
                      "0.3",
                      Patterns::Double(0., 1.),
                      "Fraction of the error (fixed fraction) or of the cells "
                      "(fixed number) marked for refinement [-].");
    prm.declare_entry("Coarsen fraction",
                      "0.03",
                      Patterns::Double(0., 1.),
                      "Fraction of the error or of the cells (smallest error) "
                      "marked for coarsening [-].");
    prm.declare_entry("Maximum level",
                      "4",
                      Patterns::Integer(0, 12),
                      "Refinement levels allowed above the initial mesh [-].");
    prm.declare_entry("Initial refinements",
                      "2",
                      Patterns::Integer(0, 12),
                      "Transient runs: adaptive refinements of the initial "
                      "temperature field [-].");
    prm.declare_entry("Steady cycles",
                      "6",
                      Patterns::Integer(1, 30),
                      "Steady runs: solve-estimate-refine cycles [-].");
    prm.leave_subsection();
  }

  void
  AdaptivityParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Adaptive refinement");
    enable              = prm.get_bool("Enable");
    strategy            = prm.get("Strategy");
    interval            = prm.get_integer("Interval");
    refine_fraction     = prm.get_double("Refine fraction");
    coarsen_fraction    = prm.get_double("Coarsen fraction");
    max_level           = prm.get_integer("Maximum level");
    initial_refinements = prm.get_integer("Initial refinements");
    steady_cycles       = prm.get_integer("Steady cycles");
    prm.leave_subsection();
    if (refine_fraction + coarsen_fraction > 1.)
      throw InputError("Adaptive refinement: Refine fraction + Coarsen "
                       "fraction must not exceed 1.");
  }

  // ----------------------------------------------------------- Heat solver
  void
  HeatSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Heat solver");
    prm.declare_entry("Polynomial degree",
                      "1",
                      Patterns::Integer(1, 3),
                      "Degree of the Lagrange elements for temperature: 1 "
                      "to 3 on quadrilaterals, 1 or 2 on triangles [-].");
    prm.declare_entry("Relative tolerance",
                      "1e-10",
                      Patterns::Double(1e-16, 1e-2),
                      "CG stops when the residual falls below this times the "
                      "right-hand side norm [-].");
    prm.declare_entry("Maximum iterations",
                      "5000",
                      Patterns::Integer(1),
                      "CG iteration limit; exceeding it stops the run with "
                      "exit status 2 [-].");
    prm.declare_entry("Preconditioner",
                      "AMG",
                      Patterns::Selection("AMG|Jacobi"),
                      "Trilinos ML algebraic multigrid, or point Jacobi.");
    prm.leave_subsection();
  }

  void
  HeatSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Heat solver");
    degree             = prm.get_integer("Polynomial degree");
    relative_tolerance = prm.get_double("Relative tolerance");
    max_iterations     = prm.get_integer("Maximum iterations");
    preconditioner     = prm.get("Preconditioner");
    prm.leave_subsection();
  }

  // ------------------------------------------------------------- Mechanics
  void
  MechanicsParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mechanics");
    prm.declare_entry(
      "Idealisation",
      "plane stress",
      Patterns::Selection("plane stress|plane strain|3D"),
      "How the mechanics treats the third direction, shared by the "
      "continuum and discrete layers. plane stress (2D, thin sheet, "
      "sigma_zz = 0): plane-stress Lame constants and in-plane thermal "
      "strain alpha dT. plane strain (2D, long body, eps_zz = 0): "
      "plane-strain Lame constants and in-plane thermal strain (1 + nu) "
      "alpha dT. 3D (Mesh/Dimension = 3, no idealisation): the 3D Lame "
      "constants and thermal strain alpha dT in every direction.");
    prm.declare_entry(
      "Strain measure",
      "small",
      Patterns::Selection("small|finite"),
      "small: linear thermoelasticity (one linear solve). finite: total "
      "Lagrangian, F = F_T F_e with F_T = (1 + beta dT) I, Cauchy stress of "
      "the paper's Eq. 44 evaluated with F_e, Newton's method with the "
      "consistent tangent (doc/theory.md, chapter 3).");
    prm.declare_entry(
      "Temperature source",
      "function",
      Patterns::Selection("function|heat solver|discrete heat"),
      "function: the temperature is Mechanics/Temperature, T(x, y, t), "
      "solved at every time step (steady: once). heat solver: the continuum "
      "heat solver runs on the same mesh (all heat entries apply, its own "
      "outputs go to <Output/Directory>/heat) and the stress is solved at "
      "each output time (and every Mechanics/Coupling interval). discrete heat: the discrete layer's heat "
      "(Discrete heat subsection: exploded P1 triangles, conducting joints) "
      "runs on the same triangle mesh, one MPI process, transient; the "
      "stress is solved at every Time step with the discrete layer's own "
      "linear field in each triangle as the temperature, so continuum and "
      "discrete thermal stresses can be compared on one temperature "
      "field.");
    prm.declare_entry("Temperature",
                      "0",
                      Patterns::Anything(),
                      "Temperature source = function: T as a function of x, "
                      "y [m] (reference coordinates) and t [s] [C]. The "
                      "stress-free temperature is the material's Reference "
                      "temperature.");
    prm.declare_entry(
      "Coupling interval",
      "0",
      Patterns::Double(0.),
      "Temperature source = heat solver, transient: the stress is solved at "
      "every output time and, with an interval > 0, also at Start time + k "
      "interval (k = 1, 2, ...; the heat steps are shortened to land on "
      "these times, which changes the heat solution slightly); 0: only at "
      "the output times [s].");
    prm.declare_entry("Polynomial degree",
                      "2",
                      Patterns::Integer(1, 3),
                      "Degree of the Lagrange elements for displacement: 1 "
                      "to 3 on quadrilaterals, 1 or 2 on triangles [-].");
    prm.declare_entry(
      "Newton tolerance",
      "1e-10",
      Patterns::Double(1e-15, 1e-2),
      "Newton stops when the residual norm falls below this times the "
      "largest residual norm of the solve (or below 1e-13 E sqrt(area), "
      "round-off) [-].");
    prm.declare_entry("Newton maximum iterations",
                      "25",
                      Patterns::Integer(1, 1000),
                      "Newton iterations per solve; not converging within "
                      "them stops the run with exit status 2 [-].");
    prm.declare_entry("Line search",
                      "true",
                      Patterns::Bool(),
                      "Backtracking line search on the residual norm (step "
                      "halved up to 10 times until the residual decreases).");
    prm.declare_entry("Linear solver tolerance",
                      "1e-12",
                      Patterns::Double(1e-16, 1e-2),
                      "CG (with algebraic multigrid) stops when the residual "
                      "falls below this times the right-hand side norm [-].");
    prm.declare_entry("Linear solver maximum iterations",
                      "5000",
                      Patterns::Integer(1),
                      "CG iteration limit; exceeding it stops the run with "
                      "exit status 2 [-].");
    prm.declare_entry("Polar frame",
                      "false",
                      Patterns::Bool(),
                      "Also write sigma_rr and sigma_tt (columns srr, stt) "
                      "about Polar centre to probes.csv and lines.csv, in the "
                      "continuum and the discrete models; the discrete "
                      "layer's solution vtu files hold them as cell data "
                      "too (srr, stt at the deformed triangle's centroid). "
                      "In 3D the frame is cylindrical about the axis "
                      "parallel to z through Polar centre (a borehole, a "
                      "cylinder of Mesh/Source = cylinder or hollow "
                      "cylinder): srr radial and stt circumferential about "
                      "that axis.");
    prm.declare_entry("Polar centre",
                      "0, 0",
                      point_pattern(),
                      "Centre of the polar frame x, y (in 3D: where its "
                      "axis, parallel to z, meets the x-y plane) [m].");
    prm.declare_entry(
      "Pinned points",
      "",
      Patterns::Anything(),
      "Mesh vertices held against rigid-body motion without restraining "
      "expansion: 'x, y: c; x, y: c' (in 3D 'x, y, z: c') with c the held "
      "components, any of x, y, z (u_x = 0, u_y = 0, u_z = 0), e.g. x, y, "
      "xy, yz, xyz; coordinates in m. Each point must be a vertex of the "
      "mesh. Example, a free annulus of outer radius b: 'b, 0: y; -b, 0: y; "
      "0, b: x'.");
    prm.leave_subsection();
  }

  void
  MechanicsParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mechanics");
    const std::string idealisation_name = prm.get("Idealisation");
    idealisation =
      idealisation_name == "plane stress" ? Idealisation::plane_stress :
      idealisation_name == "plane strain" ? Idealisation::plane_strain :
                                            Idealisation::solid_3d;
    strain_measure           = prm.get("Strain measure") == "small" ?
                                 StrainMeasure::small :
                                 StrainMeasure::finite;
    const std::string source = prm.get("Temperature source");
    temperature_source =
      source == "function"    ? TemperatureSource::function :
      source == "heat solver" ? TemperatureSource::heat_solver :
                                TemperatureSource::discrete_heat;
    temperature           = prm.get("Temperature");
    coupling_interval     = prm.get_double("Coupling interval");
    degree                = prm.get_integer("Polynomial degree");
    newton_tolerance      = prm.get_double("Newton tolerance");
    newton_max_iterations = prm.get_integer("Newton maximum iterations");
    line_search           = prm.get_bool("Line search");
    linear_tolerance      = prm.get_double("Linear solver tolerance");
    linear_max_iterations = prm.get_integer("Linear solver maximum iterations");
    polar_frame           = prm.get_bool("Polar frame");
    polar_centre          = parse_point(prm.get("Polar centre"));
    const std::string pinned = prm.get("Pinned points");
    prm.leave_subsection();

    pinned_points.clear();
    for (const auto &item : Utilities::split_string_list(pinned, ';'))
      {
        const std::string message =
          "Mechanics/Pinned points: '" + item +
          "' is not 'x, y[, z]: c' with c the held components, one or more "
          "of x, y, z (e.g. x, y, xy, xyz; coordinates in m).";
        const auto key_value = Utilities::split_string_list(item, ':');
        if (key_value.size() != 2 ||
            !space_point_pattern().match(key_value[0]) ||
            key_value[1].empty() ||
            key_value[1].find_first_not_of("xyz") != std::string::npos)
          throw InputError(message);
        PinnedPoint point;
        point.location = parse_space_point(key_value[0]);
        point.fix_x    = key_value[1].find('x') != std::string::npos;
        point.fix_y    = key_value[1].find('y') != std::string::npos;
        point.fix_z    = key_value[1].find('z') != std::string::npos;
        point.n_coordinates =
          Utilities::split_string_list(key_value[0], ',').size();
        point.text = item;
        pinned_points.push_back(point);
      }
  }

  void
  MechanicsParameters::check_dimension(const unsigned int dimension) const
  {
    if (dimension == 3 && idealisation != Idealisation::solid_3d)
      throw InputError(
        std::string("Mechanics/Idealisation = ") +
        (idealisation == Idealisation::plane_stress ? "plane stress" :
                                                      "plane strain") +
        " is a 2D idealisation; Mesh/Dimension = 3 models the third "
        "direction itself: allowed is Idealisation = 3D.");
    if (dimension == 2 && idealisation == Idealisation::solid_3d)
      throw InputError(
        "Mechanics/Idealisation = 3D needs Mesh/Dimension = 3; a 2D model "
        "takes plane stress or plane strain.");
    for (const auto &point : pinned_points)
      if ((dimension == 2 && (point.fix_z || point.n_coordinates == 3)) ||
          (dimension == 3 && point.n_coordinates != 3))
        throw InputError("Mechanics/Pinned points: '" + point.text +
                         "': Mesh/Dimension = " + std::to_string(dimension) +
                         (dimension == 2 ?
                            " takes 'x, y: c' with c one or both of x, y." :
                            " takes 'x, y, z: c' with c one or more of x, "
                            "y, z."));
  }

  // ---------------------------------------------------------------- Output
  void
  OutputParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Directory",
                      "",
                      Patterns::Anything(),
                      "Folder for all outputs; empty: output/<prm file stem> "
                      "in the working directory.");
    prm.declare_entry("Times",
                      "",
                      Patterns::List(Patterns::Double(), 0, 10000, ","),
                      "Output times [s]; the time step is shortened to land "
                      "on each. The end time is always written.");
    prm.declare_entry("Interval",
                      "0",
                      Patterns::Double(0.),
                      "Also write every this many seconds of physical time; "
                      "0: only at Times and at the end [s].");
    prm.declare_entry("Write vtu",
                      "true",
                      Patterns::Bool(),
                      "Write solution.pvd and the vtu/pvtu files for "
                      "ParaView.");
    prm.declare_entry(
      "Vtu format",
      "binary",
      Patterns::Selection("binary|ascii"),
      "Encoding of the vtu files (solution, cracks, their MPI pieces, "
      "failure_state.vtu and last_good_state.vtu): binary: VTK XML binary, "
      "every array zlib-compressed (the discrete layer: appended raw data, "
      "one zlib block per array; the continuum layer: deal.II's "
      "base64-encoded blocks), a fraction of the size, read by ParaView, "
      "VTK and meshio; ascii: the discrete layer's files as plain text, "
      "every value written as the shortest number that reads back as "
      "exactly the same value (the same arrays and values as binary); "
      "deal.II's DataOut writes the continuum layer's files base64-encoded "
      "either way, with ascii its zlib blocks uncompressed.");
    prm.declare_entry(
      "Vtu precision",
      "single",
      Patterns::Selection("single|double"),
      "Floating-point type of the discrete layer's vtu files (solution, "
      "cracks, their MPI pieces, failure_state.vtu and last_good_state.vtu): "
      "single: point coordinates and every real point and cell array as "
      "Float32, each value the double of the computation rounded to the "
      "nearest float (about 7 significant digits; the size deal.II's "
      "DataOut writes, so the continuum layer's vtu files are Float32 "
      "either way); double: as Float64, the computed doubles themselves "
      "(for comparisons to round-off). Integer arrays (connectivity, ids, "
      "failure modes) are exact either way, and Vtu format = ascii and "
      "binary hold the same values at either precision. Monitors "
      "(probes.csv, lines.csv, history.csv) do not depend on it.");
    prm.declare_entry("Write final mesh",
                      "false",
                      Patterns::Bool(),
                      "Discrete mechanics and thermo-mechanics: write the "
                      "deformed mesh at the end as <Directory>/final_mesh.msh "
                      "(gmsh 2.2 ASCII; the copies of each original vertex "
                      "averaged, material and boundary ids kept), e.g. a "
                      "settled heap as the geometry of a discrete heat run.");
    prm.declare_entry("Progress interval",
                      "2",
                      Patterns::Double(0.),
                      "Seconds of wall time between progress lines on stderr "
                      "[s].");
    prm.leave_subsection();
  }

  void
  OutputParameters::parse_parameters(ParameterHandler  &prm,
                                     const std::string &prm_stem)
  {
    prm.enter_subsection("Output");
    directory = prm.get("Directory");
    if (directory.empty())
      directory = "output/" + prm_stem;
    times = Utilities::string_to_double(
      Utilities::split_string_list(prm.get("Times"), ','));
    interval             = prm.get_double("Interval");
    write_vtu            = prm.get_bool("Write vtu");
    binary_vtu           = prm.get("Vtu format") == "binary";
    single_precision_vtu = prm.get("Vtu precision") == "single";
    write_final_mesh     = prm.get_bool("Write final mesh");
    progress_interval    = prm.get_double("Progress interval");
    prm.leave_subsection();
    for (unsigned int i = 1; i < times.size(); ++i)
      if (!(times[i] > times[i - 1]))
        throw InputError("Output/Times must increase strictly.");
  }

  // -------------------------------------------------------------- Monitors
  void
  MonitorParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Monitors");
    prm.declare_entry(
      "Probes",
      "",
      Patterns::Map(Patterns::Anything(),
                    space_point_pattern(),
                    0,
                    10000,
                    ";",
                    ":"),
      "Named probe points 'name: x, y; name2: x, y' [m] (in 3D 'name: x, "
      "y, z'); sampled into probes.csv at every output time.");
    prm.declare_entry(
      "Lines",
      "",
      Patterns::Map(Patterns::Anything(),
                    Patterns::List(Patterns::Double(), 5, 7, ","),
                    0,
                    1000,
                    ";",
                    ":"),
      "Named sampled lines 'name: x0, y0, x1, y1, n' (n >= 2 equally spaced "
      "points, x, y in m; in 3D 'name: x0, y0, z0, x1, y1, z1, n'); sampled "
      "into lines.csv at every output time.");
    prm.declare_entry(
      "Snap to nearest element",
      "false",
      Patterns::Bool(),
      "Discrete layer: a probe or line point outside the mesh (in a gap "
      "between blocks) samples the nearest point of the nearest element "
      "(in the reference configuration) instead of being an input error; "
      "lines.csv keeps the requested x, y.");
    prm.leave_subsection();
  }

  void
  MonitorParameters::parse_parameters(ParameterHandler &prm)
  {
    probes.clear();
    lines.clear();
    std::set<std::string> names;
    prm.enter_subsection("Monitors");
    for (const auto &item :
         Utilities::split_string_list(prm.get("Probes"), ';'))
      {
        const auto key_value = Utilities::split_string_list(item, ':');
        if (!names.insert(key_value[0]).second)
          throw InputError("Monitors/Probes: the name '" + key_value[0] +
                           "' is used twice.");
        probes.push_back({key_value[0], parse_space_point(key_value[1])});
      }
    for (const auto &item : Utilities::split_string_list(prm.get("Lines"), ';'))
      {
        const auto key_value = Utilities::split_string_list(item, ':');
        const auto values    = Utilities::string_to_double(
          Utilities::split_string_list(key_value[1], ','));
        if (!names.insert(key_value[0]).second)
          throw InputError("Monitors/Lines: the name '" + key_value[0] +
                           "' is used twice.");
        if (values.size() == 6)
          throw InputError("Monitors/Lines: line '" + key_value[0] +
                           "' has 6 values; allowed are 'x0, y0, x1, y1, n' "
                           "(2D) and 'x0, y0, z0, x1, y1, z1, n' (3D).");
        const bool   with_z = values.size() == 7;
        const double n      = values.back();
        if (!(n >= 2. && n <= 1e6) || n != std::floor(n))
          throw InputError("Monitors/Lines: line '" + key_value[0] +
                           "' needs an integer number of points n >= 2 as its "
                           "last value.");
        lines.push_back({key_value[0],
                         with_z ? Point<3>(values[0], values[1], values[2]) :
                                  Point<3>(values[0], values[1], 0.),
                         with_z ? Point<3>(values[3], values[4], values[5]) :
                                  Point<3>(values[2], values[3], 0.),
                         static_cast<unsigned int>(n),
                         with_z});
      }
    snap_to_nearest = prm.get_bool("Snap to nearest element");
    prm.leave_subsection();
  }

  // ------------------------------------------------------------ Checkpoint
  void
  CheckpointParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpoint");
    prm.declare_entry("Interval (steps)",
                      "0",
                      Patterns::Integer(0),
                      "Write a checkpoint every this many time steps (discrete "
                      "models; tmfdem case.prm --resume continues from the "
                      "newest); 0: not by step count [steps].");
    prm.declare_entry("Interval (wall minutes)",
                      "0",
                      Patterns::Double(0.),
                      "Write a checkpoint whenever this much wall time has "
                      "passed since the last one; 0: not by wall time [min].");
    prm.declare_entry("Directory",
                      "",
                      Patterns::Anything(),
                      "Folder of the checkpoint files; empty: "
                      "<Output/Directory>/checkpoints.");
    prm.declare_entry("Keep",
                      "2",
                      Patterns::Integer(1, 1000),
                      "Number of newest checkpoints kept; older ones are "
                      "deleted [-].");
    prm.leave_subsection();
  }

  void
  CheckpointParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpoint");
    interval_steps   = prm.get_integer("Interval (steps)");
    interval_minutes = prm.get_double("Interval (wall minutes)");
    directory        = prm.get("Directory");
    keep             = prm.get_integer("Keep");
    prm.leave_subsection();
  }

  // ---------------------------------------------------------------- Guards
  void
  GuardParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Guards");
    prm.declare_entry(
      "Kinetic energy factor",
      "100",
      Patterns::Double(0.),
      "Stop the run (discrete models) when the kinetic energy exceeds this "
      "times the energy put in (initial kinetic and strain energy, external "
      "and thermal work): a runaway; checked with every history row; 0: off "
      "[-].");
    prm.declare_entry("Stability check",
                      "true",
                      Patterns::Bool(),
                      "Stop the run (discrete models) when the time step "
                      "exceeds the stable step of the current, deformed "
                      "geometry; checked with every history row. Non-finite "
                      "values and inverted elements are always checked.");
    prm.leave_subsection();
  }

  void
  GuardParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Guards");
    kinetic_energy_factor = prm.get_double("Kinetic energy factor");
    stability_check       = prm.get_bool("Stability check");
    prm.leave_subsection();
  }

} // namespace tmfdem
