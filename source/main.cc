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

int
main(int argc, char *argv[])
{
  using namespace tmfdem;
  tmfdem::install_signal_handlers(); // SIGINT/SIGTERM during start-up too
  // Open MPI's singleton start-up (about 0.5 s of MPI_Init) is left as it
  // is: isolating the singleton (OMPI_MCA_ess_singleton_isolated=1) cut it
  // to 0.05 s but failed orte_init in 1 of 320 concurrent launches
  // (doc/performance.md); a user may still set it in the environment.
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
