/**
 * @file
 * The continuum thermo-mechanical model (`Model = continuum thermoelastic`
 * with `Mechanics/Temperature source = heat solver`): a staggered, one-way
 * coupled loop T -> u. The HeatSolver advances in time; at every coupling
 * time the ThermoelasticSolver, on the same (possibly adapted) mesh, takes
 * the current temperature field and solves for the quasi-static
 * displacement. The coupling times are the output times and, with
 * `Mechanics/Coupling interval` > 0, Start time + k interval as well.
 */
#ifndef tmfdem_coupling_continuum_thermomechanics_h
#define tmfdem_coupling_continuum_thermomechanics_h

#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>

namespace tmfdem
{
  template <int dim>
  class HeatSolver;
  template <int dim>
  class ThermoelasticSolver;

  namespace coupling
  {
    /**
     * Owns the heat solver (its outputs in <Output/Directory>/heat) and the
     * thermoelastic solver (outputs in <Output/Directory>) on the heat
     * solver's triangulation, and runs the loop between them, in @p dim
     * dimensions.
     */
    template <int dim>
    class ContinuumThermomechanics : public Simulation
    {
    public:
      ContinuumThermomechanics(const Parameters &parameters,
                               MPI_Comm          communicator);
      ~ContinuumThermomechanics() override;

      void
      check_input() override;
      void
      run() override;

    private:
      /** Steady: the heat problem (all adaptive cycles), then the stress. */
      void
      run_steady();
      /** Transient: heat steps to each coupling time, the stress there. */
      void
      run_transient();
      /** Sets up the mechanics on the heat mesh (first call) or follows its
       *  adaptation, and solves it with the temperature now at @p time [s]. */
      void
      solve_mechanics(const double time);
      /** Both models' outputs at @p time [s]. */
      void
      write_outputs(const double time);

      const Parameters                          parameters;
      MPI_Comm                                  communicator;
      std::unique_ptr<HeatSolver<dim>>          heat;
      std::unique_ptr<ThermoelasticSolver<dim>> mechanics; ///< on heat's mesh
      bool                                      mechanics_set_up = false;
    };
  } // namespace coupling
} // namespace tmfdem

#endif
