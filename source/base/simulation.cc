#include <map>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/simulation.h>

namespace tmfdem
{
  namespace
  {
    struct RegistryEntry
    {
      std::string       description;
      SimulationFactory factory;
    };

    std::map<std::string, RegistryEntry> &
    registry()
    {
      static std::map<std::string, RegistryEntry> models;
      return models;
    }
  } // namespace

  bool
  register_simulation(const std::string       &name,
                      const std::string       &description,
                      const SimulationFactory &factory)
  {
    registry()[name] = RegistryEntry{description, factory};
    return true;
  }

  std::vector<std::string>
  registered_simulation_names()
  {
    std::vector<std::string> names;
    for (const auto &entry : registry())
      names.push_back(entry.first);
    return names;
  }

  std::string
  registered_simulation_descriptions()
  {
    std::string text;
    for (const auto &entry : registry())
      text += "  " + entry.first + ": " + entry.second.description + "\n";
    return text;
  }

  std::unique_ptr<Simulation>
  create_simulation(const Parameters &parameters, MPI_Comm communicator)
  {
    const auto entry = registry().find(parameters.model);
    if (entry == registry().end())
      throw InputError("Model = '" + parameters.model +
                       "' is not a registered model; allowed:\n" +
                       registered_simulation_descriptions());
    return entry->second.factory(parameters, communicator);
  }
} // namespace tmfdem
