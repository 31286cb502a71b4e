#include <algorithm>
#include <cmath>
#include <map>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/temperature_source.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      struct SourceEntry
      {
        std::string              description;
        TemperatureSourceFactory factory;
      };

      std::map<std::string, SourceEntry> &
      source_registry()
      {
        static std::map<std::string, SourceEntry> entries;
        return entries;
      }
    } // namespace

    bool
    register_temperature_source(const std::string              &name,
                                const std::string              &description,
                                const TemperatureSourceFactory &factory)
    {
      source_registry()[name] = SourceEntry{description, factory};
      return true;
    }

    std::vector<std::string>
    temperature_source_names()
    {
      std::vector<std::string> names;
      for (const auto &entry : source_registry())
        names.push_back(entry.first);
      return names;
    }

    std::string
    temperature_source_descriptions()
    {
      std::string text;
      for (const auto &entry : source_registry())
        text += entry.first + ": " + entry.second.description + ". ";
      return text;
    }

    std::unique_ptr<TemperatureSource>
    create_temperature_source(const std::string &name,
                              const Parameters  &parameters,
                              DiscreteModel     &model,
                              MPI_Comm           communicator)
    {
      const auto entry = source_registry().find(name);
      if (entry == source_registry().end())
        {
          std::string allowed;
          for (const auto &n : temperature_source_names())
            allowed += (allowed.empty() ? "" : ", ") + n;
          throw InputError("Discrete heat/Temperature source = " + name +
                           " is not a registered source; allowed are " +
                           allowed + ".");
        }
      return entry->second.factory(parameters, model, communicator);
    }

    double
    HeatBalance::imbalance() const
    {
      double in = source_heat + contact_heat;
      for (const auto &[id, q] : boundary_heat_in)
        in += q;
      return in - stored_heat;
    }

    double
    HeatBalance::scale() const
    {
      double s = std::max({std::abs(source_heat),
                           std::abs(contact_heat),
                           contact_exchange,
                           std::abs(stored_heat),
                           1e-30});
      for (const auto &[id, q] : boundary_heat_in)
        s = std::max(s, std::abs(q));
      return s;
    }

  } // namespace discrete
} // namespace tmfdem
