/**
 * @file
 * The deal.II continuum heat solver as the temperature source of the
 * discrete layer (`Discrete heat/Temperature source = continuum heat`):
 * HeatSolver (FE_SimplexP of `Heat solver/Degree`, theta scheme of `Time
 * stepping/Method`, Trilinos CG + AMG) on the same triangle mesh, advanced at
 * every thermal step of the discrete thermo-mechanics; its field is
 * written into the discrete layer's nodal temperature vector by the L2
 * projection onto linear functions in every triangle (for P1: the vertex
 * values, exactly; for P2: the linear field with the same mean and first
 * moments in the triangle, which is what a constant-strain triangle's
 * thermal stretch can use).
 *
 * What it cannot see: it solves on the unbroken reference mesh, so heat
 * keeps crossing broken joints, no heat crosses contacts between separate
 * pieces, and the geometry does not follow the deformation. The discrete
 * layer stops at the first broken joint unless `Discrete heat/Continuum
 * source at broken joints = accept`.
 */
#ifndef tmfdem_coupling_continuum_temperature_source_h
#define tmfdem_coupling_continuum_temperature_source_h

#include <deal.II/lac/full_matrix.h>

#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/discrete/temperature_source.h>
#include <vector>

namespace tmfdem
{
  template <int dim>
  class HeatSolver;

  namespace coupling
  {
    /** Continuum heat (deal.II) feeding the discrete layer's temperatures. */
    class ContinuumTemperatureSource : public discrete::TemperatureSource
    {
    public:
      /** Checks the settings (InputError for explicit discrete heat
       *  integration, steady mode, adaptivity) and creates the solver. */
      ContinuumTemperatureSource(const Parameters        &parameters,
                                 discrete::DiscreteModel &model,
                                 MPI_Comm                 communicator);
      ~ContinuumTemperatureSource() override;

      std::string
      name() const override
      {
        return "continuum heat";
      }
      /** Name, element degree, DoFs and theta (after initialise()). */
      std::string
      describe() const override;
      void
      set_threads(const unsigned int) override
      {}
      /** Builds the continuum mesh, DoFs and matrices, matches its cells to
       *  the discrete triangles (InputError if they differ) and sets the
       *  initial temperature at @p time = Start time [s]. */
      void
      initialise(const double time) override;
      bool
      implicit() const override
      {
        return true;
      }
      double
      stable_time_step() const override;
      void
      update_contact_pairs() override
      {}
      /** One theta step of @p time_step [s] (two backward Euler half steps
       *  during a Crank-Nicolson run's Rannacher start), then the transfer
       *  to the nodes. */
      void
      step(const double time, const double time_step) override;
      Vector<double> &
      temperature() override
      {
        return nodal_temperature;
      }
      const Vector<double> &
      temperature() const override
      {
        return nodal_temperature;
      }
      const discrete::HeatBalance &
      balance() const override
      {
        return heat_balance;
      }
      const std::map<types::boundary_id, double> &
      last_boundary_rate() const override
      {
        return last_rate;
      }
      bool
      sees_cracks() const override
      {
        return false;
      }
      void
      save(CheckpointWriter &out) const override;
      void
      load(CheckpointReader &in) override;

      /** The continuum solver (after initialise()). */
      const HeatSolver<2> &
      solver() const
      {
        return *heat_solver;
      }

      /**
       * The 3 x n matrix that maps the values of a FE_SimplexP(@p degree)
       * triangle to the vertex values of its L2 projection onto linear
       * functions (reference triangle; the same for every straight
       * triangle). Identity for degree 1.
       */
      static FullMatrix<double>
      projection_to_linear(const unsigned int degree);

    private:
      /** Copies the continuum field to every rank (all_temperatures; on
       *  several ranks collective) and writes it into nodal_temperature. */
      void
      transfer();
      /** heat_balance from the solver's balance. */
      void
      copy_balance();

      const Parameters               heat_parameters;
      discrete::DiscreteModel       &model;
      MPI_Comm                       communicator;
      std::unique_ptr<HeatSolver<2>> heat_solver;
      Vector<double>                 nodal_temperature;
      /** The continuum field, every DoF, on every rank [C] (transfer()). */
      Vector<double>                       all_temperatures;
      discrete::HeatBalance                heat_balance;
      std::map<types::boundary_id, double> last_rate;

      FullMatrix<double> projection; ///< 3 x dofs per cell
      /** Per element: the DoFs of its continuum cell (dofs per cell each). */
      std::vector<types::global_dof_index> element_dofs;
      /** Per node 3e+k: the vertex of the continuum cell at that node. */
      std::vector<unsigned char> node_vertex;
    };
  } // namespace coupling
} // namespace tmfdem

#endif
