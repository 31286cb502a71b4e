/**
 * @file
 * Heat-only runs of the discrete layer (model `discrete heat`): the
 * mechanics is off, the mesh stays in its reference configuration, and the
 * run marches at the thermal step alone (Time stepping/Time step), so that
 * the paper's 50 s of conduction (Sec. 5.1) take a thousand steps, not
 * 5e8. Outputs: solution.pvd (exploded mesh with T), probes.csv and
 * lines.csv (time,name,x,y,T), summary.json with the heat balance.
 *
 * On several MPI ranks each rank advances the nodes of its own triangles
 * (ElementPartition, DiscreteHeat::distribute()): its ghosts are the
 * triangles joined to or in contact with its own, the results bitwise those
 * of one rank; each rank writes its piece of the vtu files, rank 0 the
 * rest and the checkpoints (the temperatures gathered first).
 */
#ifndef tmfdem_discrete_discrete_heat_solver_h
#define tmfdem_discrete_discrete_heat_solver_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>
#include <tmfdem/discrete/discrete_heat.h>
#include <tmfdem/discrete/discrete_mesh.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/partition.h>
#include <tmfdem/io/validation_report.h>

namespace tmfdem
{
  namespace discrete
  {
    /** Heat conduction in the discrete layer without mechanics. */
    class DiscreteHeatSolver : public Simulation, public ValidationReporter
    {
    public:
      DiscreteHeatSolver(const Parameters &parameters, MPI_Comm communicator);
      ~DiscreteHeatSolver() override;

      void
      check_input() override;
      void
      run() override;

      /** What check_input() set up, for `--validate`. */
      void
      report_validation(std::ostream     &out,
                        const Parameters &parameters,
                        MPI_Comm          communicator) const override;

      /** The exploded mesh (after check_input). */
      const DiscreteModel &
      get_model() const
      {
        return model;
      }
      /** The thermal step in use [s]. */
      double
      get_time_step() const
      {
        return time_step;
      }
      /** Stable explicit thermal step [s]; 0 with implicit integration
       *  (after check_input). */
      double
      get_stable_time_step() const
      {
        return heat && !heat->implicit() ? heat->stable_time_step() : 0.;
      }

    private:
      const Parameters             &parameters;
      MPI_Comm                      communicator;
      bool                          input_checked = false;
      Triangulation<2>              triangulation;
      FE_SimplexDGP<2>              fe;
      DoFHandler<2>                 dof_handler;
      DiscreteModel                 model;
      std::unique_ptr<DiscreteHeat> heat;
      std::vector<ReferenceSample>  probe_samples, line_samples;
      double                        time_step = 0.;
      /** Triangles of each rank (one rank: all). */
      ElementPartition partition;
      /** Triangles per chunk of the partition and of the sums. */
      static constexpr unsigned int chunk_size = 512;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
