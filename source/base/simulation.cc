#include <algorithm>
#include <map>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/simulation.h>

namespace tmfdem
{
  namespace
  {
    struct RegistryEntry
    {
      std::string               description;
      SectionsRead              sections;
      SimulationFactory         factory;
      std::vector<unsigned int> dimensions;
    };

    std::map<std::string, RegistryEntry> &
    registry()
    {
      static std::map<std::string, RegistryEntry> models;
      return models;
    }
  } // namespace

  namespace
  {
    std::string
    join(const std::vector<std::string> &names)
    {
      std::string text;
      for (const std::string &name : names)
        text += (text.empty() ? "" : ", ") + name;
      return text;
    }
  } // namespace

  std::vector<std::string>
  SectionsRead::for_input(const Parameters &parameters) const
  {
    std::vector<std::string> names = always;
    for (const Conditional &c : conditional)
      if (c.applies(parameters))
        for (const std::string &name : c.sections)
          if (std::find(names.begin(), names.end(), name) == names.end())
            names.push_back(name);
    return names;
  }

  std::string
  SectionsRead::describe() const
  {
    std::string text = join(always);
    for (const Conditional &c : conditional)
      text += "; with " + c.when + " also " + join(c.sections);
    return text;
  }

  bool
  register_simulation(const std::string               &name,
                      const std::string               &description,
                      const SectionsRead              &sections,
                      const SimulationFactory         &factory,
                      const std::vector<unsigned int> &dimensions)
  {
    registry()[name] =
      RegistryEntry{description, sections, factory, dimensions};
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

  std::string
  registered_simulation_sections()
  {
    std::string text;
    for (const auto &entry : registry())
      text +=
        "  " + entry.first + ": " + entry.second.sections.describe() + "\n";
    return text;
  }

  namespace
  {
    const RegistryEntry &
    registered_model(const Parameters &parameters)
    {
      const auto entry = registry().find(parameters.model);
      if (entry == registry().end())
        throw InputError("Model = '" + parameters.model +
                         "' is not a registered model; allowed:\n" +
                         registered_simulation_descriptions());
      return entry->second;
    }
  } // namespace

  std::vector<std::string>
  entries_not_read(const Parameters &parameters)
  {
    const std::vector<std::string> read =
      registered_model(parameters).sections.for_input(parameters);
    std::vector<std::string> not_read;
    for (const std::string &entry : parameters.changed_entries)
      {
        const auto        slash   = entry.find('/');
        const std::string section = entry.substr(0, slash);
        if (slash != std::string::npos &&
            std::find(read.begin(), read.end(), section) == read.end())
          not_read.push_back(entry);
      }
    return not_read;
  }

  std::unique_ptr<Simulation>
  create_simulation(Parameters &parameters, MPI_Comm communicator)
  {
    const RegistryEntry &model = registered_model(parameters);
    if (std::find(model.dimensions.begin(),
                  model.dimensions.end(),
                  parameters.mesh.dimension) == model.dimensions.end())
      {
        std::string allowed, models_3d;
        for (const unsigned int d : model.dimensions)
          allowed += (allowed.empty() ? "" : ", ") + std::to_string(d);
        for (const auto &[name, entry] : registry())
          if (std::find(entry.dimensions.begin(),
                        entry.dimensions.end(),
                        parameters.mesh.dimension) != entry.dimensions.end())
            models_3d += (models_3d.empty() ? "" : ", ") + name;
        throw InputError(
          "Mesh/Dimension = " + std::to_string(parameters.mesh.dimension) +
          ": Model = " + parameters.model + " runs in " + allowed +
          "D; models for this dimension: " +
          (models_3d.empty() ? "none" : models_3d) + ".");
      }
    parameters.unread_entries = entries_not_read(parameters);
    parameters.restrict_to_sections(model.sections.for_input(parameters));
    return model.factory(parameters, communicator);
  }
} // namespace tmfdem
