/**
 * @file
 * What `tmfdem --validate` checked: the mesh and model sizes, the smallest
 * element, the time steps and a memory estimate, without time stepping.
 */
#ifndef tmfdem_io_validation_report_h
#define tmfdem_io_validation_report_h

#include <mpi.h>
#include <string>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>

namespace tmfdem
{
  /**
   * Lines for the terminal about @p simulation after its check_input():
   * for the discrete models the triangles, nodes and joints, the smallest
   * element (shortest edge and smallest height [m]), the stable and used
   * time steps [s] and the steps to End time, and the memory of the model
   * state [MiB]; for the continuum heat model the smallest cell [m], the
   * steps and an estimate of the matrices' memory [MiB]; for every model the
   * resident memory after the checks [MiB]. Collective on @p communicator.
   */
  std::string
  validation_report(Simulation       &simulation,
                    const Parameters &parameters,
                    MPI_Comm          communicator);
} // namespace tmfdem

#endif
