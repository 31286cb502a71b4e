#include <map>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/continuum/temperature_field_source.h>

namespace tmfdem
{
  namespace
  {
    std::map<std::string, TemperatureFieldSourceFactory> &
    field_source_registry()
    {
      static std::map<std::string, TemperatureFieldSourceFactory> entries;
      return entries;
    }
  } // namespace

  bool
  register_temperature_field_source(
    const std::string                   &name,
    const TemperatureFieldSourceFactory &factory)
  {
    field_source_registry()[name] = factory;
    return true;
  }

  std::unique_ptr<TemperatureFieldSource>
  create_temperature_field_source(const std::string      &name,
                                  const Parameters       &parameters,
                                  const Triangulation<2> &triangulation,
                                  MPI_Comm                communicator)
  {
    const auto entry = field_source_registry().find(name);
    if (entry == field_source_registry().end())
      {
        std::string allowed;
        for (const auto &registered : field_source_registry())
          allowed += (allowed.empty() ? "" : ", ") + registered.first;
        throw InputError("Mechanics/Temperature source = " + name +
                         " is not available in this build; registered "
                         "sources are: " +
                         (allowed.empty() ? std::string("none") : allowed) +
                         ".");
      }
    return entry->second(parameters, triangulation, communicator);
  }
} // namespace tmfdem
