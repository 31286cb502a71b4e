// Unit tests of the subsections a model reads (base/simulation.h,
// Parameters::restrict_to_sections): a model receives only the subsections
// declared where it is registered, and entries set elsewhere are reported
// as not read. The expectations follow from the registrations in
// heat_solver.cc, continuum_thermomechanics.cc, explicit_solver.cc and
// discrete_heat_solver.cc.

#include <gtest/gtest.h>
#include <stdexcept>
#include <string>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <vector>

using namespace tmfdem;

TEST(ModelSections, UnreadSectionsGoBackToDefaults)
{
  Parameters parameters;
  parameters.mesh.element_size                          = 0.123;
  parameters.heat_solver.degree                         = 2;
  parameters.get<DiscreteMechanicsParameters>().threads = 2;
  parameters.restrict_to_sections({"Mesh", "Discrete mechanics"});
  EXPECT_EQ(parameters.mesh.element_size, 0.123);
  EXPECT_EQ(parameters.heat_solver.degree, HeatSolverParameters().degree);
  EXPECT_EQ(parameters.get<DiscreteMechanicsParameters>().threads, 2u);
  const std::vector<std::string> expected = {"Mesh", "Discrete mechanics"};
  EXPECT_EQ(parameters.sections_read, expected);
}

TEST(ModelSections, AnUndeclaredRegisteredSectionCannotBeRead)
{
  Parameters parameters;
  parameters.restrict_to_sections({"Mesh"});
  try
    {
      parameters.get<DiscreteHeatParameters>();
      FAIL() << "Discrete heat was read although not declared";
    }
  catch (const std::logic_error &error)
    {
      EXPECT_NE(std::string(error.what()).find("'Discrete heat'"),
                std::string::npos)
        << error.what();
    }
}

TEST(ModelSections, AnUnknownSectionIsAProgrammingError)
{
  Parameters parameters;
  EXPECT_THROW(parameters.restrict_to_sections({"Mesh", "Meshes"}),
               std::logic_error);
}

TEST(ModelSections, InitialTemperatureOfABodyGoesWithItsSection)
{
  Parameters parameters;
  parameters.initial_temperature_overrides.push_back(
    {{1}, {"100", "Discrete bodies/Body 1/Initial temperature"}});
  Parameters discrete = parameters;
  discrete.restrict_to_sections({"Materials", "Discrete bodies"});
  EXPECT_EQ(discrete.initial_temperature_of(1).expression, "100");
  parameters.restrict_to_sections({"Materials", "Initial conditions"});
  EXPECT_EQ(parameters.initial_temperature_of(1).entry,
            "Initial conditions/Temperature");
}

TEST(ModelSections, EntriesNotReadFollowTheModelAndItsInput)
{
  Parameters parameters;
  parameters.changed_entries = {"Mesh/Element size = 0.1",
                                "Heat solver/Polynomial degree = 2",
                                "Discrete heat/Coupling = quasi-static",
                                "Mechanics/Idealisation = plane strain"};
  parameters.model           = "discrete mechanics";
  EXPECT_EQ(
    entries_not_read(parameters),
    (std::vector<std::string>{"Heat solver/Polynomial degree = 2",
                              "Discrete heat/Coupling = quasi-static"}));
  // the thermo-mechanics reads the heat, the heat solver only with the
  // continuum heat as its temperature source
  parameters.model = "discrete thermo-mechanics";
  EXPECT_EQ(entries_not_read(parameters),
            (std::vector<std::string>{"Heat solver/Polynomial degree = 2"}));
  parameters.get<DiscreteHeatParameters>().temperature_source =
    "continuum heat";
  EXPECT_TRUE(entries_not_read(parameters).empty());
  // the continuum heat reads neither the discrete layer nor the mechanics
  parameters.model = "continuum heat";
  EXPECT_EQ(
    entries_not_read(parameters),
    (std::vector<std::string>{"Discrete heat/Coupling = quasi-static",
                              "Mechanics/Idealisation = plane strain"}));
  parameters.model = "continuum thermoelastic";
  EXPECT_EQ(
    entries_not_read(parameters),
    (std::vector<std::string>{"Heat solver/Polynomial degree = 2",
                              "Discrete heat/Coupling = quasi-static"}));
  parameters.mechanics.temperature_source =
    MechanicsParameters::TemperatureSource::heat_solver;
  EXPECT_EQ(entries_not_read(parameters),
            (std::vector<std::string>{
              "Discrete heat/Coupling = quasi-static"}));
}
