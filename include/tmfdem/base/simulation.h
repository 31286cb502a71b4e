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

  /**
   * The prm subsections a model reads, declared where the model is
   * registered (as ASPECT's plugins declare theirs). The model receives only
   * these (create_simulation()); entries a user sets in any other subsection
   * are reported as not read (entries_not_read()).
   */
  struct SectionsRead
  {
    /** Subsections read whatever the input, by their prm names. */
    std::vector<std::string> always;

    /** Subsections read only for some inputs. */
    struct Conditional
    {
      /** The input that makes the model read them, in words (for --help
       *  and doc/parameters.prm), e.g. "Mechanics/Temperature source =
       *  heat solver". */
      std::string              when;
      std::vector<std::string> sections;
      /** True where the parsed input is that case. */
      std::function<bool(const Parameters &)> applies;
    };
    std::vector<Conditional> conditional;

    /** The subsections read for @p parameters: always, then the
     *  conditional ones that apply. */
    std::vector<std::string>
    for_input(const Parameters &parameters) const;

    /** One line: "Mesh, Materials, ...; with <when>: ...". */
    std::string
    describe() const;
  };

  /**
   * Adds a model to the registry (done once per model, at load time).
   * @p sections names the prm subsections it reads; an unknown name is a
   * programming error (std::logic_error when the model is created).
   * @p dimensions lists the values of Mesh/Dimension the model runs; any
   * other is refused when the model is created.
   */
  bool
  register_simulation(const std::string               &name,
                      const std::string               &description,
                      const SectionsRead              &sections,
                      const SimulationFactory         &factory,
                      const std::vector<unsigned int> &dimensions = {2});

  /** Names of the registered models, for Patterns::Selection. */
  std::vector<std::string>
  registered_simulation_names();

  /** One line per model: name and description, for `--help`. */
  std::string
  registered_simulation_descriptions();

  /** For each model, the subsections it reads (SectionsRead::describe()),
   *  one model per line, for --help and doc/parameters.prm. */
  std::string
  registered_simulation_sections();

  /**
   * The entries set to other than their default in subsections that the
   * model named in @p parameters does not read ("Heat solver/Polynomial
   * degree = 2"), from Parameters::changed_entries.
   */
  std::vector<std::string>
  entries_not_read(const Parameters &parameters);

  /**
   * Creates the model named in @p parameters. First @p parameters is
   * restricted to the subsections the model reads
   * (Parameters::restrict_to_sections()): the model receives only those.
   * @p parameters must outlive the model (models keep a reference).
   */
  std::unique_ptr<Simulation>
  create_simulation(Parameters &parameters, MPI_Comm communicator);
} // namespace tmfdem

#endif
