/**
 * @file
 * The shared prm subsections Mesh, Materials and Initial conditions, the
 * registry of sections owned by other areas, and Parameters itself.
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
  using parameter_helpers::parse_space_point;
  using parameter_helpers::selection_of;
  using parameter_helpers::space_point_pattern;


  const std::vector<std::pair<std::string, double>> &
  theta_scheme_registry()
  {
    static const std::vector<std::pair<std::string, double>> methods =
      {{"backward Euler", 1.0}, {"Crank-Nicolson", 0.5}};
    return methods;
  }

  namespace
  {
    std::string
    prm_point_text(const Point<3> &p)
    {
      return "(" + Utilities::to_string(p[0]) + ", " +
             Utilities::to_string(p[1]) + ", " + Utilities::to_string(p[2]) +
             ")";
    }
  } // namespace

  // ------------------------------------------------------------------ Mesh
  void
  MeshParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    prm.declare_entry(
      "Dimension",
      "2",
      Patterns::Integer(2, 3),
      "Space dimension [-]: 2 (a plane section; quantities per unit "
      "thickness) or 3 (a solid; model continuum heat). Points are then "
      "given as x, y, z.");
    prm.declare_entry(
      "Source",
      "rectangle",
      Patterns::Selection(
        "rectangle|annulus|disc|file|block heap|box|ball|spherical shell|"
        "cylinder|hollow cylinder"),
      "Where the mesh comes from. 2D: a generated rectangle (boundary ids 0 "
      "left, 1 right, 2 bottom, 3 top), annulus (0 inner, 1 outer), disc (0 "
      "rim), or a gmsh .msh/.geo file (physical curves -> boundary ids, "
      "physical surfaces -> material ids), or a block heap (subsection Block "
      "heap: a container and seeded random convex blocks, meshed by gmsh). "
      "3D: a generated box between Lower left corner and Upper right corner "
      "(boundary ids 0 x = x0, 1 x = x1, 2 y = y0, 3 y = y1, 4 z = z0, 5 z = "
      "z1), ball (0 surface) or spherical shell (0 inner, 1 outer surface; "
      "deal.II's 6 cells refined; for tetrahedra 24, each face of the cube "
      "split in four, where that makes the cells closer to cubes: Inner "
      "radius above 0.29 Outer radius) "
      "about Center, cylinder (1 mantle, 2 bottom z = z_c - Length / 2, 3 "
      "top) or hollow cylinder (0 inner, 1 outer mantle, 2 bottom, 3 top) "
      "with its axis along z through Center, or a gmsh .msh/.geo file "
      "with tetrahedra or hexahedra "
      "(physical surfaces -> boundary ids, physical volumes -> material "
      "ids), or a block heap of polyhedral blocks in a box-shaped "
      "container (tetrahedra).");
    prm.declare_entry(
      "Element type",
      "triangles",
      Patterns::Selection("triangles|quadrilaterals"),
      "Cell shape of generated meshes: unstructured triangles (gmsh, the "
      "discrete layer's mesh) or structured quadrilaterals (continuum runs "
      "with adaptive refinement). 3D: triangles means tetrahedra (each "
      "hexahedron of the structured mesh split in 24, deal.II's "
      "convert_hypercube_to_simplex_mesh), quadrilaterals means "
      "hexahedra.");
    prm.declare_entry("Element size",
                      "0.05",
                      Patterns::Double(0.),
                      "Target edge length of generated cells [m].");
    prm.declare_entry("Lower left corner",
                      "0, 0",
                      space_point_pattern(),
                      "Rectangle: lower left corner x, y; box: the corner "
                      "x0, y0, z0 [m].");
    prm.declare_entry("Upper right corner",
                      "1, 0.25",
                      space_point_pattern(),
                      "Rectangle: upper right corner x, y; box: the corner "
                      "x1, y1, z1 [m].");
    prm.declare_entry("Center",
                      "0, 0",
                      space_point_pattern(),
                      "Annulus and disc: centre x, y; ball, spherical "
                      "shell, cylinder and hollow cylinder: centre x, y, z "
                      "(z = 0 when left out) [m].");
    prm.declare_entry("Inner radius",
                      "0.03",
                      Patterns::Double(0.),
                      "Annulus, spherical shell and hollow cylinder: inner "
                      "radius a [m].");
    prm.declare_entry("Outer radius",
                      "0.15",
                      Patterns::Double(0.),
                      "Annulus, disc, ball, spherical shell, cylinder and "
                      "hollow cylinder: outer radius b [m].");
    prm.declare_entry(
      "Radial grading",
      "1",
      Patterns::Double(1., 4.),
      "Annulus, spherical shell and hollow cylinder: the layers of cells lie "
      "at r = a + (b - a) xi^p with xi = k / (number of layers), p this "
      "value: 1 uniform layers, > 1 thinner layers at the inner surface, "
      "where a temperature like 1/r or ln r and its stress vary fastest "
      "[-].");
    prm.declare_entry("Length",
                      "0.1",
                      Patterns::Double(0.),
                      "Cylinder and hollow cylinder: length along z, "
                      "centred at Center [m].");
    prm.declare_entry("File name",
                      "",
                      Patterns::Anything(),
                      "Source = file: gmsh .msh file (format 2 or 4, ASCII), "
                      "or a gmsh .geo script that tmfdem meshes with the "
                      "gmsh program (gmsh -2 in 2D, -3 in 3D, into "
                      "<output>/mesh.msh); relative "
                      "to the folder of the prm file.");
    prm.declare_entry(
      "Gmsh time limit",
      "300",
      Patterns::Double(0.),
      "Wall-clock limit of one gmsh run [s], > 0: gmsh meshes a .geo "
      "File name, a triangle mesh of a rectangle, annulus or disc, and the "
      "block heap. Past it gmsh is stopped and the run refused (exit status "
      "1: the mesh asked for is too fine for the limit; coarsen it or raise "
      "the limit).");
    prm.declare_entry("Expected area",
                      "0",
                      Patterns::Double(0.),
                      "Source = file: the area of the domain [m^2] (in 3D "
                      "its volume [m^3]); a mesh covering less (an unmeshed "
                      "region) or more is refused. 0: not checked.");
    prm.declare_entry(
      "Circular boundaries",
      "",
      Patterns::Anything(),
      "Source = file: boundary ids whose edges lie on circles, as 'id: x, y; "
      "id: x, y' with the circle's centre x, y [m] (a hole, a borehole, a "
      "disc's rim). Global refinements put the new vertices of these edges "
      "on the circle through the edge's ends about the centre, so that the "
      "refined mesh follows the circle instead of the mesh file's polygon. "
      "Each id must name boundary edges of the mesh whose ends lie at one "
      "distance from the centre (within 1 %). Empty: refinement keeps the "
      "polygon.");
    prm.declare_entry("Global refinements",
                      "0",
                      Patterns::Integer(0, 12),
                      "Uniform refinements after generation or import [-].");
    prm.declare_entry("Material id",
                      "0",
                      Patterns::Integer(0,
                                        MaterialParameters::max_materials - 1),
                      "Material id of the cells of a generated mesh [-]; "
                      "like every id of a mesh file's cells, it needs its "
                      "subsection Materials/Material <id> in the input.");
    prm.enter_subsection("Block heap");
    {
      const BlockHeap d;
      prm.declare_entry("Container width",
                        Utilities::to_string(d.container_width),
                        Patterns::Double(0.),
                        "Inner width W of the container: the blocks lie in "
                        "0 < x < W (3D: and 0 < y < W), the base plate's top "
                        "face is y = 0 (3D: z = 0; boundary id 1, material "
                        "id 2), the side walls' inner faces x = 0 and x = W "
                        "(3D: and y = 0, y = W; boundary id 2, material id "
                        "2) [m].");
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
                        "W (3D: 0 < x, y < W, Drop height < z < Drop height "
                        "+ N s^3 / W^2) about seeded random points [-].");
      prm.declare_entry("Mean block size",
                        Utilities::to_string(d.mean_size),
                        Patterns::Double(0.),
                        "Mean block size s: the square root of the mean "
                        "Voronoi cell area (3D: the cube root of the mean "
                        "cell volume), before the gap is cut [m].");
      prm.declare_entry("Gap",
                        Utilities::to_string(d.gap),
                        Patterns::Double(0.),
                        "Clear gap between neighbouring blocks and between "
                        "blocks and walls (each Voronoi edge, in 3D each "
                        "face, is moved by Gap / 2 towards its cell's seed) "
                        "[m].");
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
    dimension                     = prm.get_integer("Dimension");
    const std::string source_name = prm.get("Source");
    source                 = source_name == "rectangle"  ? Source::rectangle :
                             source_name == "annulus"    ? Source::annulus :
                             source_name == "disc"       ? Source::disc :
                             source_name == "file"       ? Source::file :
                             source_name == "block heap" ? Source::block_heap :
                             source_name == "box"        ? Source::box :
                             source_name == "ball"       ? Source::ball :
                             source_name == "spherical shell" ? Source::spherical_shell :
                             source_name == "cylinder" ? Source::cylinder :
                                                         Source::hollow_cylinder;
    element_type           = prm.get("Element type") == "triangles" ?
                               ElementType::triangles :
                               ElementType::quadrilaterals;
    element_size           = prm.get_double("Element size");
    const auto point_entry = [&](const std::string &entry, const bool box) {
      const std::string text = prm.get(entry);
      const std::size_t n_values =
        Utilities::split_string_list(text, ',').size();
      const Point<3> p = parse_space_point(text);
      if (dimension == 2 && n_values == 3 && p[2] != 0.)
        throw InputError("Mesh/" + entry + " = " + text +
                         ": Mesh/Dimension = 2 takes a point x, y (a third "
                         "coordinate, if given, must be 0).");
      if (dimension == 3 && box && n_values != 3)
        throw InputError("Mesh/" + entry + " = " + text +
                         ": a box (Mesh/Dimension = 3) needs the corner "
                         "as x, y, z [m].");
      return p;
    };
    lower_left =
      point_entry("Lower left corner", source_name == "box" && dimension == 3);
    upper_right =
      point_entry("Upper right corner", source_name == "box" && dimension == 3);
    center             = point_entry("Center", false);
    inner_radius       = prm.get_double("Inner radius");
    outer_radius       = prm.get_double("Outer radius");
    length             = prm.get_double("Length");
    radial_grading     = prm.get_double("Radial grading");
    global_refinements = prm.get_integer("Global refinements");
    material_id        = prm.get_integer("Material id");
    file_name          = prm.get("File name");
    expected_area      = prm.get_double("Expected area");
    circular_boundaries.clear();
    for (const std::string &item :
         Utilities::split_string_list(prm.get("Circular boundaries"), ';'))
      {
        const auto fail = [&item]() {
          throw InputError("Mesh/Circular boundaries: '" + item +
                           "': allowed are entries 'boundary id: x, y' "
                           "separated by ';' (a boundary id 0 to 254 and "
                           "the circle's centre x, y in m).");
        };
        const std::vector<std::string> parts =
          Utilities::split_string_list(item, ':');
        if (parts.size() != 2)
          fail();
        const std::vector<std::string> centre =
          Utilities::split_string_list(parts[1], ',');
        int    id = -1;
        double x = 0., y = 0.;
        try
          {
            std::size_t used = 0;
            id               = std::stoi(parts[0], &used);
            if (used != parts[0].size() || centre.size() != 2)
              fail();
            x = std::stod(centre[0], &used);
            if (used != centre[0].size())
              fail();
            y = std::stod(centre[1], &used);
            if (used != centre[1].size())
              fail();
          }
        catch (const std::logic_error &)
          {
            fail();
          }
        if (id < 0 || id > 254 || !std::isfinite(x) || !std::isfinite(y))
          fail();
        for (const auto &[other, point] : circular_boundaries)
          if (other == static_cast<types::boundary_id>(id))
            throw InputError("Mesh/Circular boundaries: boundary id " +
                             std::to_string(id) +
                             " is named twice; allowed is one circle per id.");
        circular_boundaries.emplace_back(static_cast<types::boundary_id>(id),
                                         Point<2>(x, y));
        if (dimension == 3)
          throw InputError("Mesh/Circular boundaries: 2D meshes only "
                           "(Mesh/Dimension = 2).");
      }
    if (!circular_boundaries.empty() && source != Source::file)
      throw InputError("Mesh/Circular boundaries: only for Source = file "
                       "(the generated annulus and disc follow their circles "
                       "already).");
    gmsh_time_limit = prm.get_double("Gmsh time limit");
    if (!(gmsh_time_limit > 0.) || !std::isfinite(gmsh_time_limit))
      throw InputError(
        "Mesh/Gmsh time limit = " + Utilities::to_string(gmsh_time_limit) +
        ": allowed is a finite time > 0 [s].");
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

    const bool solid_source = source == Source::box || source == Source::ball ||
                              source == Source::spherical_shell ||
                              source == Source::cylinder ||
                              source == Source::hollow_cylinder;
    if (dimension == 3 && !(solid_source || source == Source::file ||
                            source == Source::block_heap))
      throw InputError("Mesh/Source = " + source_name +
                       " is a 2D domain; Mesh/Dimension = 3 allows box, "
                       "ball, spherical shell, cylinder, hollow cylinder, "
                       "file and block heap.");
    if (dimension == 2 && solid_source)
      throw InputError("Mesh/Source = " + source_name +
                       " is a 3D domain: set Mesh/Dimension = 3 (2D allows "
                       "rectangle, annulus, disc, file and block heap).");
    if (source == Source::box &&
        !(upper_right[0] > lower_left[0] && upper_right[1] > lower_left[1] &&
          upper_right[2] > lower_left[2]))
      throw InputError("Mesh: a box needs Upper right corner > Lower left "
                       "corner in x, y and z; got " +
                       prm_point_text(lower_left) + " and " +
                       prm_point_text(upper_right) + ".");
    if (source == Source::spherical_shell &&
        !(outer_radius > inner_radius && inner_radius > 0.))
      throw InputError("Mesh: a spherical shell needs 0 < Inner radius < "
                       "Outer radius; got Inner radius = " +
                       std::to_string(inner_radius) + ", Outer radius = " +
                       std::to_string(outer_radius) + ".");
    if (source == Source::ball && !(outer_radius > 0.))
      throw InputError("Mesh/Outer radius must be > 0 for a ball.");
    if (source == Source::hollow_cylinder &&
        !(outer_radius > inner_radius && inner_radius > 0.))
      throw InputError("Mesh: a hollow cylinder needs 0 < Inner radius < "
                       "Outer radius; got Inner radius = " +
                       std::to_string(inner_radius) + ", Outer radius = " +
                       std::to_string(outer_radius) + ".");
    if (radial_grading != 1. && source != Source::annulus &&
        source != Source::spherical_shell && source != Source::hollow_cylinder)
      throw InputError(
        "Mesh/Radial grading = " + Utilities::to_string(radial_grading) +
        ": grades the layers of an annulus, spherical shell or "
        "hollow cylinder; Mesh/Source = " +
        source_name + " takes 1.");
    if (source == Source::cylinder && !(outer_radius > 0.))
      throw InputError("Mesh/Outer radius must be > 0 for a cylinder.");
    if ((source == Source::cylinder || source == Source::hollow_cylinder) &&
        !(length > 0. && std::isfinite(length)))
      throw InputError("Mesh/Length = " + Utilities::to_string(length) +
                       ": a cylinder needs a finite length > 0 [m].");
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

  void
  MaterialParameters::require_given(const types::material_id id,
                                    const std::string       &where) const
  {
    (*this)[id]; // ids beyond the subsections
    if (given[id])
      return;
    std::string defined;
    for (unsigned int other = 0; other < max_materials; ++other)
      if (given[other])
        defined += (defined.empty() ? "" : ", ") + std::to_string(other);
    throw InputError(
      "material id " + std::to_string(id) + " is used by " + where +
      ", but the input has no subsection Materials/Material " +
      std::to_string(id) +
      ": it would run on built-in default properties. Define it (subsection "
      "Materials, subsection Material " +
      std::to_string(id) + ": Density, Young's modulus, ...)" +
      (defined.empty() ?
         std::string("; the input defines no Materials/Material <id>.") :
         "; the input defines Material " + defined + ".") +
      " (tmfdem --print-parameters lists the entries.)");
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
    if (found != map.end())
      return *found->second;
    for (const ParameterSectionType &t : registered_parameter_sections())
      if (t.type == type)
        throw std::logic_error(
          "Parameters::get: the subsection '" + t.name +
          "' is not among those this model reads: add it to the "
          "SectionsRead where the model is registered (register_simulation)");
    throw std::logic_error(
      std::string("Parameters::get: no parameter section of type ") +
      type.name() + " is registered (register_parameter_section)");
  }

  void
  ParameterSections::keep_only(const std::vector<std::string> &names)
  {
    for (const ParameterSectionType &t : registered_parameter_sections())
      if (std::find(names.begin(), names.end(), t.name) == names.end())
        map.erase(t.type);
  }

  // ------------------------------------------- the subsections a model reads
  namespace
  {
    /** A shared subsection: its prm name and how to reset it. */
    struct SharedSection
    {
      const char *name;
      void (*reset)(Parameters &);
    };

    const std::vector<SharedSection> &
    shared_sections()
    {
      static const std::vector<SharedSection> sections = {
        {"Mesh", [](Parameters &p) { p.mesh = {}; }},
        {"Materials", [](Parameters &p) { p.materials = {}; }},
        {"Thermal boundary conditions",
         [](Parameters &p) { p.thermal_boundary = {}; }},
        {"Initial conditions", [](Parameters &p) { p.initial = {}; }},
        {"Time stepping", [](Parameters &p) { p.time = {}; }},
        {"Adaptive refinement", [](Parameters &p) { p.adaptivity = {}; }},
        {"Heat solver", [](Parameters &p) { p.heat_solver = {}; }},
        {"Output", [](Parameters &p) { p.output = {}; }},
        {"Monitors", [](Parameters &p) { p.monitors = {}; }},
        {"Mechanics", [](Parameters &p) { p.mechanics = {}; }},
        {"Mechanical boundary conditions",
         [](Parameters &p) { p.mechanical_boundary = {}; }},
        {"Checkpoint", [](Parameters &p) { p.checkpoint = {}; }},
        {"Guards", [](Parameters &p) { p.guards = {}; }}};
      return sections;
    }
  } // namespace

  std::vector<std::string>
  Parameters::section_names()
  {
    std::vector<std::string> names;
    for (const SharedSection &s : shared_sections())
      names.emplace_back(s.name);
    for (const ParameterSectionType &t : registered_parameter_sections())
      names.push_back(t.name);
    return names;
  }

  void
  Parameters::restrict_to_sections(const std::vector<std::string> &names)
  {
    const std::vector<std::string> all = section_names();
    for (const std::string &name : names)
      if (std::find(all.begin(), all.end(), name) == all.end())
        throw std::logic_error("a model declares that it reads the prm "
                               "subsection '" +
                               name + "', which does not exist");
    const auto reads = [&names](const std::string &name) {
      return std::find(names.begin(), names.end(), name) != names.end();
    };
    for (const SharedSection &s : shared_sections())
      if (!reads(s.name))
        s.reset(*this);
    // an initial temperature goes with the subsection of its entry
    initial_temperature_overrides.erase(
      std::remove_if(initial_temperature_overrides.begin(),
                     initial_temperature_overrides.end(),
                     [&reads](const InitialTemperatureOverride &o) {
                       const std::string &entry = o.temperature.entry;
                       return !reads(entry.substr(0, entry.find('/')));
                     }),
      initial_temperature_overrides.end());
    sections.keep_only(names);
    sections_read = names;
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
    mechanical_boundary.check_dimension(mesh.dimension);
    if (mesh.dimension == 2)
      {
        for (const auto &probe : monitors.probes)
          if (probe.location[2] != 0.)
            throw InputError(
              "Monitors/Probes: probe '" + probe.name +
              "' has z = " + Utilities::to_string(probe.location[2]) +
              "; Mesh/Dimension = 2 takes points x, y.");
        for (const auto &line : monitors.lines)
          if (line.with_z)
            throw InputError("Monitors/Lines: line '" + line.name +
                             "' is given with z coordinates; Mesh/Dimension "
                             "= 2 takes 'x0, y0, x1, y1, n'.");
      }
    // an output time before the start is never reached
    for (const double t : output.times)
      if (t < time.start_time)
        throw InputError("Output/Times: " + Utilities::to_string(t) +
                         " s is before Time stepping/Start time = " +
                         Utilities::to_string(time.start_time) +
                         " s and would never be written; allowed are times "
                         ">= Start time (negative times only with a negative "
                         "Start time).");

    // what the registered sections add to the shared ones (initial
    // temperatures of bodies), and their checks across sections
    initial_temperature_overrides.clear();
    for (const ParameterSectionType &type : registered_parameter_sections())
      sections.find(type.type).complete(*this);
    // malformed expressions are refused here, naming the entry, whichever
    // layer runs and whether or not the mesh has that material
    for (unsigned int id = 0; id < MaterialParameters::max_materials; ++id)
      if (!materials.materials[id].initial_temperature.empty())
        {
          const std::string entry =
            "Materials/Material " + std::to_string(id) + "/Initial temperature";
          if (mesh.dimension == 3)
            make_expression_function<3>(
              materials.materials[id].initial_temperature,
              entry);
          else
            make_expression_function(
              materials.materials[id].initial_temperature,
              entry);
        }
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
