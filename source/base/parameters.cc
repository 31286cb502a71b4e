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

namespace tmfdem
{
  namespace
  {
    /** "a, b" -> Point; the pattern has already checked the format. */
    Point<2>
    parse_point(const std::string &text)
    {
      const std::vector<double> values =
        Utilities::string_to_double(Utilities::split_string_list(text, ','));
      return Point<2>(values[0], values[1]);
    }

    std::string
    selection_of(const std::vector<std::string> &names)
    {
      std::string result;
      for (const auto &name : names)
        result += (result.empty() ? "" : "|") + name;
      return result;
    }

    const auto point_pattern = Patterns::List(Patterns::Double(), 2, 2, ",");
  } // namespace

  const std::vector<std::pair<std::string, double>> &
  theta_scheme_registry()
  {
    static const std::vector<std::pair<std::string, double>> methods =
      {{"backward Euler", 1.0}, {"Crank-Nicolson", 0.5}};
    return methods;
  }

  // ------------------------------------------------------------------ Mesh
  void
  MeshParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    prm.declare_entry(
      "Source",
      "rectangle",
      Patterns::Selection("rectangle|annulus|disc|file|block heap"),
      "Where the mesh comes from: a generated rectangle (boundary ids 0 left, "
      "1 right, 2 bottom, 3 top), annulus (0 inner, 1 outer), disc (0 rim), "
      "or a gmsh .msh/.geo file (physical curves -> boundary ids, physical "
      "surfaces -> material ids), or a block heap (subsection Block heap: "
      "a container and seeded random convex blocks, meshed by gmsh).");
    prm.declare_entry(
      "Element type",
      "triangles",
      Patterns::Selection("triangles|quadrilaterals"),
      "Cell shape of generated meshes: unstructured triangles (gmsh, the "
      "discrete layer's mesh) or structured quadrilaterals (continuum runs "
      "with adaptive refinement).");
    prm.declare_entry("Element size",
                      "0.05",
                      Patterns::Double(0.),
                      "Target edge length of generated cells [m].");
    prm.declare_entry("Lower left corner",
                      "0, 0",
                      point_pattern,
                      "Rectangle: lower left corner x, y [m].");
    prm.declare_entry("Upper right corner",
                      "1, 0.25",
                      point_pattern,
                      "Rectangle: upper right corner x, y [m].");
    prm.declare_entry("Center",
                      "0, 0",
                      point_pattern,
                      "Annulus and disc: centre x, y [m].");
    prm.declare_entry("Inner radius",
                      "0.03",
                      Patterns::Double(0.),
                      "Annulus: inner radius a [m].");
    prm.declare_entry("Outer radius",
                      "0.15",
                      Patterns::Double(0.),
                      "Annulus and disc: outer radius b [m].");
    prm.declare_entry("File name",
                      "",
                      Patterns::Anything(),
                      "Source = file: gmsh .msh file (format 2 or 4, ASCII), "
                      "or a gmsh .geo script that tmfdem meshes with the "
                      "gmsh program (2D, into <output>/mesh.msh); relative "
                      "to the folder of the prm file.");
    prm.declare_entry("Expected area",
                      "0",
                      Patterns::Double(0.),
                      "Source = file: the area of the domain [m^2]; a mesh "
                      "covering less (an unmeshed region) or more is "
                      "refused. 0: not checked.");
    prm.declare_entry("Global refinements",
                      "0",
                      Patterns::Integer(0, 12),
                      "Uniform refinements after generation or import [-].");
    prm.declare_entry("Material id",
                      "0",
                      Patterns::Integer(0,
                                        MaterialParameters::max_materials - 1),
                      "Material id of the cells of a generated mesh [-].");
    prm.enter_subsection("Block heap");
    {
      const BlockHeap d;
      prm.declare_entry("Container width",
                        Utilities::to_string(d.container_width),
                        Patterns::Double(0.),
                        "Inner width W of the container: the blocks lie in "
                        "0 < x < W, the base plate's top face is y = 0 "
                        "(boundary id 1, material id 2), the side walls' "
                        "inner faces x = 0 and x = W (boundary id 2, "
                        "material id 2) [m].");
      prm.declare_entry("Container height",
                        Utilities::to_string(d.container_height),
                        Patterns::Double(0.),
                        "Height H of the side walls above the base [m].");
      prm.declare_entry("Wall thickness",
                        Utilities::to_string(d.wall_thickness),
                        Patterns::Double(0.),
                        "Thickness of the base plate and of the side walls "
                        "[m].");
      prm.declare_entry("Number of blocks",
                        std::to_string(d.n_blocks),
                        Patterns::Integer(1, 10000),
                        "Number of blocks (material id 1, boundary id 0), "
                        "the cells of a Voronoi tessellation of the region "
                        "0 < x < W, Drop height < y < Drop height + N s^2 / "
                        "W about seeded random points [-].");
      prm.declare_entry("Mean block size",
                        Utilities::to_string(d.mean_size),
                        Patterns::Double(0.),
                        "Mean block size s: the square root of the mean "
                        "Voronoi cell area (before the gap is cut) [m].");
      prm.declare_entry("Gap",
                        Utilities::to_string(d.gap),
                        Patterns::Double(0.),
                        "Clear gap between neighbouring blocks and between "
                        "blocks and walls (each Voronoi edge is moved by "
                        "Gap / 2 towards its cell's seed) [m].");
      prm.declare_entry("Drop height",
                        Utilities::to_string(d.drop_height),
                        Patterns::Double(0.),
                        "Height of the region's bottom above the base: the "
                        "lowest blocks fall at least this far [m].");
      prm.declare_entry("Seed",
                        std::to_string(d.seed),
                        Patterns::Integer(0),
                        "Seed of the random generator (std::mt19937); the "
                        "same seed gives the same blocks and mesh [-].");
    }
    prm.leave_subsection();
    prm.leave_subsection();
  }

  void
  MeshParameters::parse_parameters(ParameterHandler  &prm,
                                   const std::string &input_folder)
  {
    prm.enter_subsection("Mesh");
    const std::string source_name = prm.get("Source");
    source             = source_name == "rectangle" ? Source::rectangle :
                         source_name == "annulus"   ? Source::annulus :
                         source_name == "disc"      ? Source::disc :
                         source_name == "file"      ? Source::file :
                                                      Source::block_heap;
    element_type       = prm.get("Element type") == "triangles" ?
                           ElementType::triangles :
                           ElementType::quadrilaterals;
    element_size       = prm.get_double("Element size");
    lower_left         = parse_point(prm.get("Lower left corner"));
    upper_right        = parse_point(prm.get("Upper right corner"));
    center             = parse_point(prm.get("Center"));
    inner_radius       = prm.get_double("Inner radius");
    outer_radius       = prm.get_double("Outer radius");
    global_refinements = prm.get_integer("Global refinements");
    material_id        = prm.get_integer("Material id");
    file_name          = prm.get("File name");
    expected_area      = prm.get_double("Expected area");
    prm.enter_subsection("Block heap");
    block_heap.container_width  = prm.get_double("Container width");
    block_heap.container_height = prm.get_double("Container height");
    block_heap.wall_thickness   = prm.get_double("Wall thickness");
    block_heap.n_blocks         = prm.get_integer("Number of blocks");
    block_heap.mean_size        = prm.get_double("Mean block size");
    block_heap.gap              = prm.get_double("Gap");
    block_heap.drop_height      = prm.get_double("Drop height");
    block_heap.seed             = prm.get_integer("Seed");
    prm.leave_subsection();
    prm.leave_subsection();
    // the block heap's own checks run where it is generated
    // (mesh/block_generator.h), before any output is written

    if (source != Source::file && !(element_size > 0.))
      throw InputError("Mesh/Element size = " + std::to_string(element_size) +
                       ": must be > 0 [m].");
    if (source == Source::rectangle &&
        !(upper_right[0] > lower_left[0] && upper_right[1] > lower_left[1]))
      throw InputError("Mesh/Upper right corner must lie above and to the "
                       "right of Mesh/Lower left corner.");
    if (source == Source::annulus &&
        !(outer_radius > inner_radius && inner_radius > 0.))
      throw InputError("Mesh: an annulus needs 0 < Inner radius < Outer "
                       "radius; got Inner radius = " +
                       std::to_string(inner_radius) + ", Outer radius = " +
                       std::to_string(outer_radius) + ".");
    if (source == Source::disc && !(outer_radius > 0.))
      throw InputError("Mesh/Outer radius must be > 0 for a disc.");
    if (source == Source::file)
      {
        if (file_name.empty())
          throw InputError("Mesh/Source = file needs Mesh/File name.");
        if (std::filesystem::path(file_name).is_relative())
          file_name =
            (std::filesystem::path(input_folder) / file_name).string();
      }
  }

  // ------------------------------------------------------------- Materials
  void
  MaterialParameters::declare_parameters(ParameterHandler &prm)
  {
    const MaterialProperties defaults;
    prm.enter_subsection("Materials");
    for (unsigned int id = 0; id < max_materials; ++id)
      {
        prm.enter_subsection("Material " + std::to_string(id));
        prm.declare_entry("Density",
                          Utilities::to_string(defaults.density),
                          Patterns::Double(0.),
                          "Mass density rho [kg/m^3], > 0.");
        prm.declare_entry("Young's modulus",
                          Utilities::to_string(defaults.youngs_modulus),
                          Patterns::Double(0.),
                          "Young's modulus E [Pa], > 0.");
        prm.declare_entry("Poisson's ratio",
                          Utilities::to_string(defaults.poisson_ratio),
                          Patterns::Double(-1., 0.5),
                          "Poisson's ratio nu [-], -1 < nu < 0.5.");
        prm.declare_entry("Thermal conductivity",
                          Utilities::to_string(defaults.thermal_conductivity),
                          Patterns::Double(0.),
                          "Thermal conductivity k [W/(m K)], > 0, of an "
                          "isotropic material. Leave it at its default where "
                          "the principal values 'Thermal conductivity along' "
                          "and 'across' are given.");
        prm.declare_entry(
          "Thermal conductivity along",
          "",
          Patterns::List(Patterns::Double(0.), 0, 1),
          "Anisotropic conduction (paper Eqs. 8-9): principal conductivity "
          "k1 [W/(m K)], > 0, along the direction d = (cos theta, sin "
          "theta) of 'Conductivity direction'. Empty: isotropic "
          "('Thermal conductivity'). Give 'Thermal conductivity across' "
          "with it; K = k1 d d^T + k2 p p^T, p perpendicular to d.");
        prm.declare_entry(
          "Thermal conductivity across",
          "",
          Patterns::List(Patterns::Double(0.), 0, 1),
          "Anisotropic conduction: principal conductivity k2 [W/(m K)], "
          "> 0, across the direction d (along p = (-sin theta, cos "
          "theta)). Empty: isotropic. Give 'Thermal conductivity along' "
          "with it.");
        prm.declare_entry(
          "Conductivity direction",
          "0",
          Patterns::Double(-360., 360.),
          "Angle theta of the principal direction d of 'Thermal "
          "conductivity along', counterclockwise from the x axis [deg], "
          "in the reference configuration (the discrete layer turns the "
          "tensor with each triangle's rotation). Only with the "
          "principal values set.");
        prm.declare_entry("Specific heat capacity",
                          Utilities::to_string(defaults.specific_heat),
                          Patterns::Double(0.),
                          "Specific heat capacity c_p [J/(kg K)], > 0.");
        prm.declare_entry("Thermal expansion coefficient",
                          Utilities::to_string(defaults.thermal_expansion),
                          Patterns::Double(0.),
                          "Linear thermal expansion coefficient alpha [1/K].");
        prm.declare_entry("Reference temperature",
                          Utilities::to_string(defaults.reference_temperature),
                          Patterns::Double(-273.15),
                          "Stress-free temperature T_ref [C].");
        prm.declare_entry("Tensile strength",
                          Utilities::to_string(defaults.tensile_strength),
                          Patterns::Double(0.),
                          "Tensile strength f_t of the joints [Pa].");
        prm.declare_entry("Cohesion",
                          Utilities::to_string(defaults.cohesion),
                          Patterns::Double(0.),
                          "Cohesion c of the joints' Mohr-Coulomb shear "
                          "strength [Pa].");
        prm.declare_entry("Internal friction angle",
                          Utilities::to_string(defaults.friction_angle),
                          Patterns::Double(0., 89.),
                          "Internal friction angle phi [deg].");
        prm.declare_entry("Mode I fracture energy",
                          Utilities::to_string(defaults.fracture_energy_I),
                          Patterns::Double(0.),
                          "Mode I fracture energy G_I [J/m^2].");
        prm.declare_entry("Mode II fracture energy",
                          Utilities::to_string(defaults.fracture_energy_II),
                          Patterns::Double(0.),
                          "Mode II fracture energy G_II [J/m^2].");
        prm.declare_entry("Volumetric heat source",
                          defaults.heat_source,
                          Patterns::Anything(),
                          "Heat generated per unit volume, a function of x, y "
                          "[m] and t [s] [W/m^3].");
        prm.declare_entry(
          "Initial temperature",
          "",
          Patterns::Anything(),
          "Initial temperature of this material's cells, a function of x, y "
          "[m] (t = start time) [C]; empty: Initial conditions/Temperature. "
          "Precedence: Discrete bodies/Body <n>/Initial temperature > this > "
          "Initial conditions/Temperature (setting it here and for a body "
          "containing this material is refused). Discrete layer: exact per "
          "triangle (each owns its nodes); continuum (CG): a node shared by "
          "cells of different initial temperatures takes the mean of their "
          "values there.");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }

  void
  MaterialParameters::parse_parameters(ParameterHandler &prm)
  {
    const MaterialProperties defaults;
    prm.enter_subsection("Materials");
    for (unsigned int id = 0; id < max_materials; ++id)
      {
        const std::string name = "Materials/Material " + std::to_string(id);
        prm.enter_subsection("Material " + std::to_string(id));
        MaterialProperties &m  = materials[id];
        m.density              = prm.get_double("Density");
        m.youngs_modulus       = prm.get_double("Young's modulus");
        m.poisson_ratio        = prm.get_double("Poisson's ratio");
        m.thermal_conductivity = prm.get_double("Thermal conductivity");
        m.specific_heat        = prm.get_double("Specific heat capacity");
        m.thermal_expansion = prm.get_double("Thermal expansion coefficient");
        m.reference_temperature = prm.get_double("Reference temperature");
        m.tensile_strength      = prm.get_double("Tensile strength");
        m.cohesion              = prm.get_double("Cohesion");
        m.friction_angle        = prm.get_double("Internal friction angle");
        m.fracture_energy_I     = prm.get_double("Mode I fracture energy");
        m.fracture_energy_II    = prm.get_double("Mode II fracture energy");
        m.heat_source           = prm.get("Volumetric heat source");
        const std::string along = Utilities::trim(
                            prm.get("Thermal conductivity along")),
                          across = Utilities::trim(
                            prm.get("Thermal conductivity across"));
        m.conductivity_direction = prm.get_double("Conductivity direction");
        m.initial_temperature = Utilities::trim(prm.get("Initial temperature"));
        prm.leave_subsection();

        // anisotropic conduction: both principal values or neither, and
        // not together with a changed isotropic value
        m.anisotropic_conductivity = !along.empty() || !across.empty();
        if (along.empty() != across.empty())
          throw InputError(
            name + "/Thermal conductivity " +
            (along.empty() ? "across" : "along") + " is set but " + name +
            "/Thermal conductivity " + (along.empty() ? "along" : "across") +
            " is not: give both principal values (anisotropic conduction) "
            "or neither (isotropic, 'Thermal conductivity').");
        if (m.anisotropic_conductivity)
          {
            m.conductivity_along  = Utilities::string_to_double(along);
            m.conductivity_across = Utilities::string_to_double(across);
            for (const auto &[entry, value] :
                 {std::pair<const char *, double>{"along",
                                                  m.conductivity_along},
                  {"across", m.conductivity_across}})
              if (!(value > 0.))
                throw InputError(name + "/Thermal conductivity " + entry +
                                 " = " + Utilities::to_string(value) +
                                 ": must be > 0.");
            if (m.thermal_conductivity != defaults.thermal_conductivity)
              throw InputError(
                name + "/Thermal conductivity = " +
                Utilities::to_string(m.thermal_conductivity) +
                " contradicts the principal values 'Thermal conductivity "
                "along' = " +
                along + " and 'across' = " + across +
                " of the same material: an anisotropic material takes its "
                "conductivity from along/across only; remove 'Thermal "
                "conductivity' (leave it at its default " +
                Utilities::to_string(defaults.thermal_conductivity) +
                ") or the principal values.");
          }
        else if (m.conductivity_direction != 0.)
          throw InputError(
            name + "/Conductivity direction = " +
            Utilities::to_string(m.conductivity_direction) +
            " deg has no effect on an isotropic material: set 'Thermal "
            "conductivity along' and 'Thermal conductivity across' (the "
            "principal values) or leave the direction at 0.");

        if (!(m.poisson_ratio < 0.5) || !(m.poisson_ratio > -1.))
          throw InputError(name + "/Poisson's ratio = " +
                           Utilities::to_string(m.poisson_ratio) +
                           ": allowed is -1 < nu < 0.5 (0.5 is "
                           "incompressible, which a displacement "
                           "formulation cannot represent).");
        const std::pair<const char *, double> positive[] = {
          {"Density", m.density},
          {"Young's modulus", m.youngs_modulus},
          {"Thermal conductivity", m.thermal_conductivity},
          {"Specific heat capacity", m.specific_heat}};
        for (const auto &[entry, value] : positive)
          if (!(value > 0.))
            throw InputError(name + "/" + entry + " = " +
                             Utilities::to_string(value) + ": must be > 0.");
      }
    prm.leave_subsection();
  }

  const MaterialProperties &
  MaterialParameters::operator[](const types::material_id id) const
  {
    if (id >= max_materials)
      throw InputError("Material id " + std::to_string(id) +
                       " has no subsection: allowed ids are 0 ... " +
                       std::to_string(max_materials - 1) +
                       " (Materials/Material <id>).");
    return materials[id];
  }

  // ------------------------------------------- Thermal boundary conditions
  void
  ThermalBoundaryParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Thermal boundary conditions");
    for (unsigned int n = 1; n <= max_conditions; ++n)
      {
        prm.enter_subsection("Condition " + std::to_string(n));
        prm.declare_entry("Boundary ids",
                          "",
                          Patterns::List(Patterns::Integer(0), 0, 1000, ","),
                          "Boundary ids this condition applies to (empty: "
                          "unused). Boundary ids named by no condition are "
                          "insulated.");
        prm.declare_entry("Type",
                          "dirichlet",
                          Patterns::Selection("dirichlet|neumann|robin"),
                          "dirichlet: T = Temperature; neumann: inward heat "
                          "flux q = Heat flux; robin (convective): inward "
                          "flux h (T_inf - T).");
        prm.declare_entry("Temperature",
                          "0",
                          Patterns::Anything(),
                          "Dirichlet temperature, function of x, y [m], t [s] "
                          "[C].");
        prm.declare_entry("Heat flux",
                          "0",
                          Patterns::Anything(),
                          "Neumann heat flux into the body, function of x, y, "
                          "t [W/m^2].");
        prm.declare_entry("Heat transfer coefficient",
                          "0",
                          Patterns::Anything(),
                          "Robin heat transfer coefficient h, function of x, "
                          "y, t [W/(m^2 K)].");
        prm.declare_entry("Ambient temperature",
                          "0",
                          Patterns::Anything(),
                          "Robin ambient (fluid) temperature T_inf, function "
                          "of x, y, t [C].");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }

  void
  ThermalBoundaryParameters::parse_parameters(ParameterHandler &prm)
  {
    conditions.clear();
    std::set<types::boundary_id> used;
    prm.enter_subsection("Thermal boundary conditions");
    for (unsigned int n = 1; n <= max_conditions; ++n)
      {
        ThermalBoundaryCondition condition;
        condition.name =
          "Thermal boundary conditions/Condition " + std::to_string(n);
        prm.enter_subsection("Condition " + std::to_string(n));
        for (const int id : Utilities::string_to_int(
               Utilities::split_string_list(prm.get("Boundary ids"), ',')))
          condition.boundary_ids.push_back(id);
        const std::string type = prm.get("Type");
        condition.type =
          type == "dirichlet" ? ThermalBoundaryCondition::Type::dirichlet :
          type == "neumann"   ? ThermalBoundaryCondition::Type::neumann :
                                ThermalBoundaryCondition::Type::robin;
        condition.temperature = prm.get("Temperature");
        condition.heat_flux   = prm.get("Heat flux");
        condition.heat_transfer_coefficient =
          prm.get("Heat transfer coefficient");
        condition.ambient_temperature = prm.get("Ambient temperature");
        prm.leave_subsection();
        for (const auto id : condition.boundary_ids)
          if (!used.insert(id).second)
            throw InputError(condition.name + "/Boundary ids: boundary id " +
                             std::to_string(id) +
                             " already has a thermal condition; each boundary "
                             "id takes at most one.");
        if (!condition.boundary_ids.empty())
          conditions.push_back(condition);
      }
    prm.leave_subsection();
  }

  // --------------------------------------------------- Initial conditions
  void
  InitialConditionParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Temperature",
                      "0",
                      Patterns::Anything(),
                      "Initial temperature, function of x, y [m] (t = start "
                      "time) [C].");
    prm.declare_entry(
      "Stress free",
      "false",
      Patterns::Bool(),
      "Discrete thermo-mechanics: true: the body is stress free at its "
      "initial temperature field (heated slowly to it before t = 0, as a "
      "specimen before a quench), in place of the materials' Reference "
      "temperature; false: the thermal strain is measured from the "
      "Reference temperature.");
    prm.leave_subsection();
  }

  void
  InitialConditionParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Initial conditions");
    temperature = prm.get("Temperature");
    stress_free = prm.get_bool("Stress free");
    prm.leave_subsection();
  }

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
                      "Degree of the Lagrange elements for temperature [-].");
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
      Patterns::Selection("plane stress|plane strain"),
      "2D idealisation, shared by the continuum and discrete layers. plane "
      "stress (thin sheet, sigma_zz = 0): plane-stress Lame constants and "
      "in-plane thermal strain alpha dT. plane strain (long body, eps_zz = "
      "0): plane-strain Lame constants and in-plane thermal strain (1 + nu) "
      "alpha dT.");
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
                      "Degree of the Lagrange elements for displacement [-].");
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
                      "about Polar centre to probes.csv and lines.csv.");
    prm.declare_entry("Polar centre",
                      "0, 0",
                      point_pattern,
                      "Centre of the polar frame x, y [m].");
    prm.declare_entry(
      "Pinned points",
      "",
      Patterns::Anything(),
      "Mesh vertices held against rigid-body motion without restraining "
      "expansion: 'x, y: c; x, y: c' with c = x (u_x = 0), y (u_y = 0) or xy "
      "(both), x, y in m. Each point must be a vertex of the coarse mesh. "
      "Example, a free annulus of outer radius b: 'b, 0: y; -b, 0: y; 0, b: "
      "x'.");
    prm.leave_subsection();
  }

  void
  MechanicsParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mechanics");
    idealisation             = prm.get("Idealisation") == "plane stress" ?
                                 Idealisation::plane_stress :
                                 Idealisation::plane_strain;
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
          "' is not 'x, y: c' with c = x, y or xy (x, y in m).";
        const auto key_value = Utilities::split_string_list(item, ':');
        if (key_value.size() != 2 || !point_pattern.match(key_value[0]) ||
            (key_value[1] != "x" && key_value[1] != "y" &&
             key_value[1] != "xy"))
          throw InputError(message);
        PinnedPoint point;
        point.location = parse_point(key_value[0]);
        point.fix_x    = key_value[1].find('x') != std::string::npos;
        point.fix_y    = key_value[1].find('y') != std::string::npos;
        point.text     = item;
        pinned_points.push_back(point);
      }
  }

  // ---------------------------------------- Mechanical boundary conditions
  void
  MechanicalBoundaryParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mechanical boundary conditions");
    for (unsigned int n = 1; n <= max_conditions; ++n)
      {
        prm.enter_subsection("Condition " + std::to_string(n));
        prm.declare_entry("Boundary ids",
                          "",
                          Patterns::List(Patterns::Integer(0), 0, 1000, ","),
                          "Boundary ids this condition applies to (empty: "
                          "unused). Boundary ids named by no condition are "
                          "traction free.");
        prm.declare_entry(
          "Type",
          "fixed",
          Patterns::Selection(
            "fixed|roller x|roller y|displacement|traction|velocity"),
          "fixed: u = 0; roller x: u_x = 0 (u_y free); roller y: u_y = 0 "
          "(u_x free); displacement: u = (Displacement x, Displacement y); "
          "traction: nominal traction (Traction x, Traction y), force per "
          "unit reference length; velocity: v = (Velocity x, Velocity y), "
          "discrete layer only (the continuum solver refuses it).");
        const char *axes[] = {"x", "y"};
        for (const char *axis : axes)
          {
            prm.declare_entry(std::string("Displacement ") + axis,
                              "0",
                              Patterns::Anything(),
                              std::string("Type = displacement: u_") + axis +
                                " as a function of x, y [m] (reference "
                                "coordinates) and t [s] [m].");
            prm.declare_entry(std::string("Traction ") + axis,
                              "0",
                              Patterns::Anything(),
                              std::string("Type = traction: t_") + axis +
                                " per unit reference length, function of x, "
                                "y, t [Pa].");
            prm.declare_entry(std::string("Velocity ") + axis,
                              "0",
                              Patterns::Anything(),
                              std::string("Type = velocity (discrete layer "
                                          "only): v_") +
                                axis + ", function of x, y, t [m/s].");
          }
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }

  void
  MechanicalBoundaryParameters::parse_parameters(ParameterHandler &prm)
  {
    using Type = MechanicalBoundaryCondition::Type;
    conditions.clear();
    std::set<types::boundary_id> used;
    prm.enter_subsection("Mechanical boundary conditions");
    for (unsigned int n = 1; n <= max_conditions; ++n)
      {
        MechanicalBoundaryCondition condition;
        condition.name =
          "Mechanical boundary conditions/Condition " + std::to_string(n);
        prm.enter_subsection("Condition " + std::to_string(n));
        for (const int id : Utilities::string_to_int(
               Utilities::split_string_list(prm.get("Boundary ids"), ',')))
          condition.boundary_ids.push_back(id);
        const std::string type = prm.get("Type");
        condition.type         = type == "fixed"        ? Type::fixed :
                                 type == "roller x"     ? Type::roller_x :
                                 type == "roller y"     ? Type::roller_y :
                                 type == "displacement" ? Type::displacement :
                                 type == "traction"     ? Type::traction :
                                                          Type::velocity;
        const char *axes[]     = {"x", "y"};
        for (unsigned int d = 0; d < 2; ++d)
          {
            condition.displacement[d] =
              prm.get(std::string("Displacement ") + axes[d]);
            condition.traction[d] = prm.get(std::string("Traction ") + axes[d]);
            condition.velocity[d] = prm.get(std::string("Velocity ") + axes[d]);
          }
        prm.leave_subsection();
        for (const auto id : condition.boundary_ids)
          if (!used.insert(id).second)
            throw InputError(condition.name + "/Boundary ids: boundary id " +
                             std::to_string(id) +
                             " already has a mechanical condition; each "
                             "boundary id takes at most one.");
        if (!condition.boundary_ids.empty())
          conditions.push_back(condition);
      }
    prm.leave_subsection();
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
    interval          = prm.get_double("Interval");
    write_vtu         = prm.get_bool("Write vtu");
    write_final_mesh  = prm.get_bool("Write final mesh");
    progress_interval = prm.get_double("Progress interval");
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
      Patterns::Map(Patterns::Anything(), point_pattern, 0, 10000, ";", ":"),
      "Named probe points 'name: x, y; name2: x, y' [m]; sampled into "
      "probes.csv at every output time.");
    prm.declare_entry(
      "Lines",
      "",
      Patterns::Map(Patterns::Anything(),
                    Patterns::List(Patterns::Double(), 5, 5, ","),
                    0,
                    1000,
                    ";",
                    ":"),
      "Named sampled lines 'name: x0, y0, x1, y1, n' (n >= 2 equally spaced "
      "points, x, y in m); sampled into lines.csv at every output time.");
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
        probes.push_back({key_value[0], parse_point(key_value[1])});
      }
    for (const auto &item : Utilities::split_string_list(prm.get("Lines"), ';'))
      {
        const auto key_value = Utilities::split_string_list(item, ':');
        const auto values    = Utilities::string_to_double(
          Utilities::split_string_list(key_value[1], ','));
        if (!names.insert(key_value[0]).second)
          throw InputError("Monitors/Lines: the name '" + key_value[0] +
                           "' is used twice.");
        if (!(values[4] >= 2. && values[4] <= 1e6) ||
            values[4] != std::floor(values[4]))
          throw InputError("Monitors/Lines: line '" + key_value[0] +
                           "' needs an integer number of points n >= 2 as its "
                           "fifth value.");
        lines.push_back({key_value[0],
                         Point<2>(values[0], values[1]),
                         Point<2>(values[2], values[3]),
                         static_cast<unsigned int>(values[4])});
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

  // ------------------------------------------------- registered sections
  namespace
  {
    std::vector<ParameterSectionType> &
    section_registry()
    {
      static std::vector<ParameterSectionType> registry;
      return registry;
    }
  } // namespace

  const std::vector<ParameterSectionType> &
  registered_parameter_sections()
  {
    return section_registry();
  }

  bool
  add_parameter_section(ParameterSectionType type)
  {
    for (const auto &t : section_registry())
      if (t.type == type.type || t.name == type.name)
        throw std::logic_error("the parameter section '" + type.name +
                               "' is registered twice");
    section_registry().push_back(std::move(type));
    return true;
  }

  ParameterSections::ParameterSections()
  {
    for (const ParameterSectionType &type : registered_parameter_sections())
      map.emplace(type.type, type.create());
  }

  ParameterSections::ParameterSections(const ParameterSections &other)
  {
    *this = other;
  }

  ParameterSections &
  ParameterSections::operator=(const ParameterSections &other)
  {
    if (this == &other)
      return *this;
    map.clear();
    for (const auto &[type, section] : other.map)
      map.emplace(type, section->clone());
    return *this;
  }

  ParameterSections::~ParameterSections() = default;

  ParameterSection &
  ParameterSections::find(const std::type_index &type) const
  {
    const auto found = map.find(type);
    if (found == map.end())
      throw std::logic_error(
        std::string("Parameters::get: no parameter section of type ") +
        type.name() + " is registered (register_parameter_section)");
    return *found->second;
  }

  // ------------------------------------------------------------ Parameters
  void
  Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Model",
                      "continuum heat",
                      Patterns::Selection(
                        selection_of(registered_simulation_names())),
                      "What tmfdem solves; see tmfdem --help for the list.");
    MeshParameters::declare_parameters(prm);
    MaterialParameters::declare_parameters(prm);
    ThermalBoundaryParameters::declare_parameters(prm);
    InitialConditionParameters::declare_parameters(prm);
    TimeSteppingParameters::declare_parameters(prm);
    AdaptivityParameters::declare_parameters(prm);
    HeatSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm);
    MonitorParameters::declare_parameters(prm);
    MechanicsParameters::declare_parameters(prm);
    MechanicalBoundaryParameters::declare_parameters(prm);
    for (const ParameterSectionType &type : registered_parameter_sections())
      type.declare(prm);
    CheckpointParameters::declare_parameters(prm);
    GuardParameters::declare_parameters(prm);
  }

  void
  Parameters::parse_parameters(ParameterHandler &prm)
  {
    const std::filesystem::path path(prm_file);
    model = prm.get("Model");
    mesh.parse_parameters(prm, path.parent_path().string());
    materials.parse_parameters(prm);
    thermal_boundary.parse_parameters(prm);
    initial.parse_parameters(prm);
    time.parse_parameters(prm);
    adaptivity.parse_parameters(prm);
    heat_solver.parse_parameters(prm);
    output.parse_parameters(prm, path.stem().string());
    monitors.parse_parameters(prm);
    mechanics.parse_parameters(prm);
    mechanical_boundary.parse_parameters(prm);
    for (const ParameterSectionType &type : registered_parameter_sections())
      sections.find(type.type).parse(prm);
    checkpoint.parse_parameters(prm);
    guards.parse_parameters(prm);

    // what the registered sections add to the shared ones (initial
    // temperatures of bodies), and their checks across sections
    initial_temperature_overrides.clear();
    for (const ParameterSectionType &type : registered_parameter_sections())
      sections.find(type.type).complete(*this);
    // malformed expressions are refused here, naming the entry, whichever
    // layer runs and whether or not the mesh has that material
    for (unsigned int id = 0; id < MaterialParameters::max_materials; ++id)
      if (!materials.materials[id].initial_temperature.empty())
        make_expression_function(materials.materials[id].initial_temperature,
                                 "Materials/Material " + std::to_string(id) +
                                   "/Initial temperature");
  }

  InitialTemperatureEntry
  Parameters::initial_temperature_of(const types::material_id id) const
  {
    for (const auto &o : initial_temperature_overrides)
      if (std::find(o.material_ids.begin(), o.material_ids.end(), id) !=
          o.material_ids.end())
        return o.temperature;
    if (id < MaterialParameters::max_materials &&
        !materials.materials[id].initial_temperature.empty())
      return {materials.materials[id].initial_temperature,
              "Materials/Material " + std::to_string(id) +
                "/Initial temperature"};
    return {initial.temperature, "Initial conditions/Temperature"};
  }

  bool
  Parameters::has_local_initial_temperature() const
  {
    if (!initial_temperature_overrides.empty())
      return true;
    for (const auto &m : materials.materials)
      if (!m.initial_temperature.empty())
        return true;
    return false;
  }
} // namespace tmfdem
