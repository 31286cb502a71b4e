/**
 * @file
 * Error classes that decide the exit status of a tmfdem run.
 */
#ifndef tmfdem_base_exceptions_h
#define tmfdem_base_exceptions_h

#include <stdexcept>
#include <string>

namespace tmfdem
{
  /**
   * Bad input: a parameter file, a command-line override, a mesh file or a
   * combination of them that tmfdem refuses. The message names the file,
   * entry or element and what is allowed. `main` turns it into exit status 1.
   */
  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * A failure during a run whose input was valid (a linear solver that does
   * not converge, an output file that cannot be written). `main` turns it
   * into exit status 2.
   */
  class RunError : public std::runtime_error
  {
  public:
    explicit RunError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * The run stopped on SIGINT or SIGTERM after finishing its step and
   * writing its outputs and a checkpoint (resume with --resume). `main`
   * prints the message and returns exit status 3.
   */
  class StopRequested : public std::runtime_error
  {
  public:
    explicit StopRequested(const std::string &message)
      : std::runtime_error(message)
    {}
  };
} // namespace tmfdem

#endif
