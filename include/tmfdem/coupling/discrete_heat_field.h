/**
 * @file
 * The discrete layer's heat as the temperature of the continuum
 * thermoelastic model (`Mechanics/Temperature source = discrete heat`):
 * DiscreteHeat (exploded P1 triangles, conducting joints, its boundary
 * conditions and time integration) on the thermoelastic model's own
 * triangle mesh, advanced to every load step; the thermoelastic quadrature
 * points take the discrete layer's own linear field of their triangle (no
 * averaging across joints: the same field the discrete mechanics would
 * use), so continuum and discrete thermal stresses can be set side by side
 * on one temperature field. Registered as the continuum layer's
 * TemperatureFieldSource "discrete heat".
 */
#ifndef tmfdem_coupling_discrete_heat_field_h
#define tmfdem_coupling_discrete_heat_field_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/tria.h>

#include <functional>
#include <memory>
#include <mpi.h>
#include <tmfdem/base/parameters.h>
#include <tmfdem/continuum/temperature_field_source.h>
#include <tmfdem/discrete/discrete_model.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    class DiscreteHeat;
  }

  namespace coupling
  {
    /** Discrete heat evaluated as a temperature field on its triangulation. */
    class DiscreteHeatField : public TemperatureFieldSource
    {
    public:
      /** Sets up the discrete heat on @p triangulation (triangles, one MPI
       *  process; InputError otherwise) and its initial temperature at
       *  Time stepping/Start time. */
      DiscreteHeatField(const Parameters       &parameters,
                        const Triangulation<2> &triangulation,
                        MPI_Comm                communicator);
      ~DiscreteHeatField() override;

      /** Advances the heat to @p time [s] in steps of Time stepping/Time
       *  step (the last one shortened to land on @p time). */
      void
      advance_to(const double time) override;

      /** The discrete layer's own linear field of each triangle at the
       *  current time, valid while this object lives. */
      TemperatureField
      field() const override;

      /** Time of the current temperatures [s]. */
      double
      current_time() const
      {
        return time;
      }

      /** Relative heat imbalance so far [-]. */
      double
      relative_imbalance() const;

    private:
      const Parameters                       &parameters;
      FE_SimplexDGP<2>                        fe;
      DoFHandler<2>                           dof_handler;
      discrete::DiscreteModel                 model;
      std::unique_ptr<discrete::DiscreteHeat> heat;
      double                                  time = 0.;
    };
  } // namespace coupling
} // namespace tmfdem

#endif
