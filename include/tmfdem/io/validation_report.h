/**
 * @file
 * What `tmfdem --validate` checked: the mesh and model sizes, the smallest
 * element, the time steps and a memory estimate, without time stepping.
 * io owns the interface (ValidationReporter); each model implements it and
 * writes its own lines, so io knows no model.
 */
#ifndef tmfdem_io_validation_report_h
#define tmfdem_io_validation_report_h

#include <mpi.h>
#include <ostream>
#include <string>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>

namespace tmfdem
{
  /**
   * A model that tells `--validate` what its check_input() set up. Models
   * derive from it next to Simulation; validation_report() calls it.
   */
  class ValidationReporter
  {
  public:
    virtual ~ValidationReporter() = default;

    /**
     * Writes lines for the terminal to @p out (on every process; rank 0's
     * are printed): sizes, the smallest element [m], the time steps [s],
     * the memory of the model's state [MiB]. Called after check_input().
     * Collective on @p communicator.
     */
    virtual void
    report_validation(std::ostream     &out,
                      const Parameters &parameters,
                      MPI_Comm          communicator) const = 0;
  };

  namespace validation
  {
    /** Bytes in a mebibyte. */
    constexpr double mebibyte = 1024. * 1024.;

    /**
     * One line "  what: stable .. s, used .. s, N steps to End time = .. s"
     * (@p stable [s] left out where it is 0, the steps where @p used is 0).
     */
    void
    describe_steps(std::ostream      &out,
                   const std::string &what,
                   const double       stable,
                   const double       used,
                   const Parameters  &parameters);
  } // namespace validation

  /**
   * Lines for the terminal about @p simulation after its check_input(): the
   * model's own (ValidationReporter, where it is one), the prm subsections
   * it read and the entries it did not, and the resident memory after the
   * checks [MiB]. Collective on @p communicator.
   */
  std::string
  validation_report(Simulation       &simulation,
                    const Parameters &parameters,
                    MPI_Comm          communicator);
} // namespace tmfdem

#endif
