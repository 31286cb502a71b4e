/**
 * @file
 * Temperatures that another layer computes on the continuum thermoelastic
 * model's own mesh (`Mechanics/Temperature source = discrete heat`). The
 * continuum layer owns this interface and its registry; the layer that
 * computes the temperatures implements it and registers itself by the
 * prm's name (coupling/discrete_heat_field.h), so the thermoelastic solver
 * does not know who computes them.
 */
#ifndef tmfdem_continuum_temperature_field_source_h
#define tmfdem_continuum_temperature_field_source_h

#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <functional>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace tmfdem
{
  using namespace dealii;
  struct Parameters;

  /**
   * Temperature [C] at @p points (real coordinates [m]) of @p cell, which
   * are @p unit_points in its reference cell, at the time of the current
   * solve; written into @p temperatures (same size as the points).
   */
  template <int dim>
  using TemperatureFieldOf = std::function<
    void(const typename Triangulation<dim>::active_cell_iterator &cell,
         const std::vector<Point<dim>>                           &unit_points,
         const std::vector<Point<dim>>                           &points,
         std::vector<double> &temperatures)>;

  /** The 2D field, which the sources of other layers provide. */
  using TemperatureField = TemperatureFieldOf<2>;

  /** A temperature field computed by another layer on the mesh of the
   *  thermoelastic model, advanced in time by that layer. */
  class TemperatureFieldSource
  {
  public:
    virtual ~TemperatureFieldSource() = default;

    /** Advances the temperatures to @p time [s]. */
    virtual void
    advance_to(const double time) = 0;

    /** The field at the current time, valid while this object lives. */
    virtual TemperatureField
    field() const = 0;
  };

  /** Builds a source on the thermoelastic model's @p triangulation at
   *  Time stepping/Start time; InputError where it cannot run there. */
  using TemperatureFieldSourceFactory = std::function<
    std::unique_ptr<TemperatureFieldSource>(const Parameters &,
                                            const Triangulation<2> &,
                                            MPI_Comm)>;

  /** Adds a source under the `Mechanics/Temperature source` value @p name
   *  (once, at load time). */
  bool
  register_temperature_field_source(
    const std::string                   &name,
    const TemperatureFieldSourceFactory &factory);

  /** Creates the source registered as @p name; InputError for an unknown
   *  one, listing the registered names. */
  std::unique_ptr<TemperatureFieldSource>
  create_temperature_field_source(const std::string      &name,
                                  const Parameters       &parameters,
                                  const Triangulation<2> &triangulation,
                                  MPI_Comm                communicator);
} // namespace tmfdem

#endif
