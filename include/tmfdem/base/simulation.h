/**
 * @file
 * The model registry: every kind of run (continuum heat, and the models that
 * later issues add) registers a factory under the name users select with the
 * top-level prm entry `Model`.
 */
#ifndef tmfdem_base_simulation_h
#define tmfdem_base_simulation_h

#include <functional>
#include <memory>
#include <mpi.h>
#include <string>
#include <tmfdem/base/parameters.h>
#include <vector>

namespace tmfdem
{
  /** A run of one model, built from validated parameters. */
  class Simulation
  {
  public:
    virtual ~Simulation() = default;
    /**
     * Build everything that depends on the input (mesh, boundary ids,
     * materials, monitors) and check it, without solving. Throws InputError.
     */
    virtual void
    check_input() = 0;
    /** Run to the end; outputs are written as the run goes. */
    virtual void
    run() = 0;
  };

  using SimulationFactory =
    std::function<std::unique_ptr<Simulation>(const Parameters &, MPI_Comm)>;

  /** Adds a model to the registry (done once per model, at load time). */
  bool
  register_simulation(const std::string       &name,
                      const std::string       &description,
                      const SimulationFactory &factory);

  /** Names of the registered models, for Patterns::Selection. */
  std::vector<std::string>
  registered_simulation_names();

  /** One line per model: name and description, for `--help`. */
  std::string
  registered_simulation_descriptions();

  /** Creates the model named in @p parameters. */
  std::unique_ptr<Simulation>
  create_simulation(const Parameters &parameters, MPI_Comm communicator);
} // namespace tmfdem

#endif
