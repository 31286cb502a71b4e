/**
 * @file
 * Where the discrete layer's nodal temperatures come from: its own heat
 * conduction (DiscreteHeat, `Discrete heat/Temperature source = discrete
 * heat`) or another solver that writes into the same vector (the deal.II
 * continuum heat on the same triangle mesh, coupling/continuum_temperature_
 * source.h). The thermo-mechanical loop of ExplicitSolver talks to this
 * interface only, once per thermal step (no virtual call per element).
 */
#ifndef tmfdem_discrete_temperature_source_h
#define tmfdem_discrete_temperature_source_h

#include <deal.II/base/types.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <map>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace tmfdem
{
  using namespace dealii;
  class CheckpointWriter;
  class CheckpointReader;
  struct Parameters;

  namespace discrete
  {
    struct ContactPair;
    class ElementPartition;

    struct DiscreteModel;

    /** Heat that crossed each boundary id, joints and contacts, and the
     *  stored heat [J/m] (per unit thickness). */
    struct HeatBalance
    {
      std::map<types::boundary_id, double> boundary_heat_in;
      double                               source_heat  = 0.;
      double                               contact_heat = 0.; ///< sums to 0
      /** Heat that crossed contacts, sum over pairs of |Q| dt [J/m]. */
      double contact_exchange = 0.;
      double stored_heat      = 0.;
      /** in - stored [J/m]. */
      double
      imbalance() const;
      /** Largest of the terms [J/m]. */
      double
      scale() const;
    };

    /**
     * The temperature field of the discrete layer: nodal values [C] indexed
     * like the DoFs of FE_SimplexDGP(1) on the discrete triangulation (node
     * 3e+k is vertex k of element e), advanced in time by step().
     */
    class TemperatureSource
    {
    public:
      virtual ~TemperatureSource() = default;

      /** Name under which the source is registered. */
      virtual std::string
      name() const = 0;

      /** One line for `--validate`: the source and its discretisation. */
      virtual std::string
      describe() const
      {
        return name();
      }

      /** Threads the source may use (its results do not depend on it). */
      virtual void
      set_threads(const unsigned int threads) = 0;

      /** Sets the temperatures at Start time @p time [s]. */
      virtual void
      initialise(const double time) = 0;

      /** True if step() may take any step (implicit time integration). */
      virtual bool
      implicit() const = 0;

      /** Largest stable step of an explicit source [s]; +inf if implicit. */
      virtual double
      stable_time_step() const = 0;

      /** The geometry or the joints changed (call before step()): a source
       *  that sees contacts finds its conducting pairs again. */
      virtual void
      update_contact_pairs() = 0;

      /**
       * The mechanics' contact candidates (ContactSystem::pairs(), a
       * superset of the overlapping pairs while its search is current), for
       * a source that sees contacts to take its conducting pairs from
       * instead of searching itself; nullptr: search itself. The caller
       * keeps @p candidates alive and current before update_contact_pairs().
       */
      virtual void
      share_contact_candidates(const std::vector<ContactPair> *candidates)
      {
        (void)candidates;
      }

      /**
       * Runs the source on the ranks of @p partition: each rank advances
       * the nodes of its own triangles and keeps its ghosts' temperatures
       * current (the ghost plan of @p partition), and the reductions are
       * exact, so the temperatures are bitwise those of one rank. Call
       * before initialise(). Returns false for a source that runs only
       * replicated (every rank the whole field from the whole state): the
       * caller then synchronises the state before every step().
       */
      virtual bool
      distribute(ElementPartition &partition)
      {
        (void)partition;
        return false;
      }

      /** Advances from @p time by @p time_step [s]. */
      virtual void
      step(const double time, const double time_step) = 0;

      /** Nodal temperatures [C]. */
      virtual Vector<double> &
      temperature() = 0;
      virtual const Vector<double> &
      temperature() const = 0;

      /** Heat balance since the start [J/m]. */
      virtual const HeatBalance &
      balance() const = 0;

      /** Heat rate through each boundary id in the last step [W/m]. */
      virtual const std::map<types::boundary_id, double> &
      last_boundary_rate() const = 0;

      /** True if heat stops at broken joints and crosses contacts (the
       *  discrete heat); false for a source on the unbroken mesh. */
      virtual bool
      sees_cracks() const = 0;

      /** Appends the state to a checkpoint. */
      virtual void
      save(CheckpointWriter &out) const = 0;
      /** Restores what save() wrote; InputError on a mismatch. */
      virtual void
      load(CheckpointReader &in) = 0;
    };

    /** Builds a source for @p model from the parameters (one MPI process). */
    using TemperatureSourceFactory =
      std::function<std::unique_ptr<TemperatureSource>(const Parameters &,
                                                       DiscreteModel &,
                                                       MPI_Comm)>;

    /** Adds a source to the registry (once, at load time). */
    bool
    register_temperature_source(const std::string              &name,
                                const std::string              &description,
                                const TemperatureSourceFactory &factory);

    /** Registered names, for `Discrete heat/Temperature source`. */
    std::vector<std::string>
    temperature_source_names();

    /** One line per source (name: description), for the prm doc string. */
    std::string
    temperature_source_descriptions();

    /** Creates the source named @p name; InputError for an unknown one. */
    std::unique_ptr<TemperatureSource>
    create_temperature_source(const std::string &name,
                              const Parameters  &parameters,
                              DiscreteModel     &model,
                              MPI_Comm           communicator);
  } // namespace discrete
} // namespace tmfdem

#endif
