/**
 * @file
 * The prm subsections Thermal boundary conditions and Mechanical boundary
 * conditions.
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
  using parameter_helpers::point_pattern;
  using parameter_helpers::selection_of;

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
            "fixed|roller x|roller y|roller z|displacement|traction|"
            "velocity"),
          "fixed: u = 0; roller x: u_x = 0 (the other components free); "
          "roller y: u_y = 0; roller z: u_z = 0 (3D); displacement: u = "
          "(Displacement x, Displacement y[, Displacement z]); traction: "
          "nominal traction (Traction x, Traction y[, Traction z]), force "
          "per unit reference length (2D) or area (3D); velocity: v = "
          "(Velocity x, Velocity y[, Velocity z]), every component held "
          "(one not set is held at 0: a face pulled along x does not "
          "contract sideways), discrete layer only (the continuum solver "
          "refuses it).");
        for (const char *axis : {"z"})
          {
            prm.declare_entry(std::string("Displacement ") + axis,
                              "0",
                              Patterns::Anything(),
                              "Type = displacement, Mesh/Dimension = 3: u_z "
                              "as a function of x, y, z [m] (reference "
                              "coordinates) and t [s] [m].");
            prm.declare_entry(std::string("Traction ") + axis,
                              "0",
                              Patterns::Anything(),
                              "Type = traction, Mesh/Dimension = 3: t_z per "
                              "unit reference area, function of x, y, z, t "
                              "[Pa].");
            prm.declare_entry(std::string("Velocity ") + axis,
                              "0",
                              Patterns::Anything(),
                              "Type = velocity (discrete layer only), "
                              "Mesh/Dimension = 3: v_z, function of x, y, z "
                              "(reference coordinates), t [m/s].");
          }
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
                                 type == "roller z"     ? Type::roller_z :
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
        condition.displacement[2] = prm.get("Displacement z");
        condition.traction[2]     = prm.get("Traction z");
        condition.velocity[2]     = prm.get("Velocity z");
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

  void
  MechanicalBoundaryParameters::check_dimension(
    const unsigned int dimension) const
  {
    if (dimension == 3)
      return;
    for (const auto &condition : conditions)
      {
        if (condition.type == MechanicalBoundaryCondition::Type::roller_z)
          throw InputError(condition.name +
                           "/Type = roller z: a 2D model has no z "
                           "displacement; allowed are fixed, roller x, "
                           "roller y, displacement, traction, velocity.");
        const bool z_entry =
          (condition.type == MechanicalBoundaryCondition::Type::displacement &&
           condition.displacement[2] != "0") ||
          (condition.type == MechanicalBoundaryCondition::Type::traction &&
           condition.traction[2] != "0") ||
          (condition.type == MechanicalBoundaryCondition::Type::velocity &&
           condition.velocity[2] != "0");
        if (z_entry)
          throw InputError(
            condition.name + "/" +
            (condition.type == MechanicalBoundaryCondition::Type::traction ?
               "Traction z = " + condition.traction[2] :
             condition.type == MechanicalBoundaryCondition::Type::velocity ?
               "Velocity z = " + condition.velocity[2] :
               "Displacement z = " + condition.displacement[2]) +
            ": Mesh/Dimension = 2 has no z component; allowed is 0.");
      }
  }

} // namespace tmfdem
