/**
 * The tmfdem program: parse the command line, read the prm file, run the
 * selected model. Exit status 0 on success, 1 on bad input, 2 on a failure
 * during the run (guards included), 3 when stopped by SIGINT/SIGTERM after
 * writing a checkpoint.
 */
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <cstdlib>
#include <iostream>
#include <tmfdem/base/command_line.h>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/simulation.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/validation_report.h>

namespace
{
  /**
   * Started without a launcher (no mpirun, srun, ...), Open MPI 4.1 makes
   * the process a singleton: MPI_Init starts a support daemon and probes
   * the network, about 0.5 s of a small case's 0.7 s. A process that is
   * not launched as one rank of several never needs either, so tmfdem asks
   * Open MPI for an isolated singleton (no daemon) with only the self
   * transport, and without session directories: isolated singletons all
   * share the job id [0,1] and so the session directory
   * /tmp/ompi.HOST.UID/jf.0/1, which one process removes at MPI_Finalize
   * while another creates it (orte_init failed in 1 of 320 concurrent
   * launches; doc/performance.md, "Start-up time"). Settings in the
   * environment win (setenv does not overwrite).
   */
  void
  isolate_open_mpi_singleton()
  {
    for (const char *launched : {"OMPI_COMM_WORLD_SIZE",
                                 "PMIX_RANK",
                                 "PMI_RANK",
                                 "PMI_SIZE",
                                 "SLURM_PROCID"})
      if (std::getenv(launched) != nullptr)
        return;
    setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
    setenv("OMPI_MCA_orte_create_session_dirs", "0", 0);
    setenv("OMPI_MCA_pml", "ob1", 0);
    setenv("OMPI_MCA_btl", "self", 0);
  }
} // namespace

int
main(int argc, char *argv[])
{
  using namespace tmfdem;
  tmfdem::install_signal_handlers(); // SIGINT/SIGTERM during start-up too
  isolate_open_mpi_singleton();
  dealii::Utilities::MPI::MPI_InitFinalize
    mpi(argc, argv, dealii::numbers::invalid_unsigned_int);
  // ranks x threads <= cores (include/tmfdem/base/threads.h)
  tmfdem::set_thread_limit(tmfdem::core_share(MPI_COMM_WORLD).cores_per_rank);
  const bool root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  dealii::deal_II_exceptions::disable_abort_on_exception();
  try
    {
      const CommandLine command_line = parse_command_line(argc, argv);
      switch (command_line.action)
        {
          case CommandLine::Action::help:
            if (root)
              std::cout << usage_text();
            return 0;
          case CommandLine::Action::print_parameters:
            if (root)
              std::cout << default_parameter_file();
            return 0;
          default:
            break;
        }
      Parameters parameters =
        read_parameters(command_line.prm_file, command_line.overrides);
      parameters.resume = command_line.resume;
      install_signal_handlers();
      auto simulation = create_simulation(parameters, MPI_COMM_WORLD);
      if (root && !parameters.unread_entries.empty())
        {
          std::cerr << "tmfdem: warning: Model = " << parameters.model
                    << " does not read these entries of "
                    << command_line.prm_file << " (their subsections are "
                    << "not among those it reads; tmfdem --help lists them):";
          for (const std::string &entry : parameters.unread_entries)
            std::cerr << "\n  " << entry;
          std::cerr << std::endl;
        }
      if (command_line.action == CommandLine::Action::validate)
        {
          simulation->check_input();
          const std::string report =
            validation_report(*simulation, parameters, MPI_COMM_WORLD);
          if (root)
            std::cout << report << command_line.prm_file << ": valid"
                      << std::endl;
          return 0;
        }
      simulation->run();
    }
  catch (const StopRequested &stop)
    {
      if (root)
        std::cerr << "tmfdem: " << stop.what() << std::endl;
      return 3;
    }
  catch (const InputError &error)
    {
      if (root)
        std::cerr << "tmfdem: error in the input: " << error.what()
                  << std::endl;
      return 1;
    }
  catch (const RunError &error)
    {
      if (root)
        std::cerr << "tmfdem: the run failed: " << error.what() << std::endl;
      return 2;
    }
  catch (const dealii::ExceptionBase &exception)
    {
      std::cerr << "tmfdem: the run failed with an internal error:\n";
      exception.print_info(std::cerr);
      std::cerr << std::endl;
      return 2;
    }
  catch (const std::exception &exception)
    {
      std::cerr << "tmfdem: the run failed: " << exception.what() << std::endl;
      return 2;
    }
  return 0;
}
