/**
 * @file
 * The command line of the tmfdem program and the reading of a prm file with
 * its `--set` overrides.
 */
#ifndef tmfdem_base_command_line_h
#define tmfdem_base_command_line_h

#include <string>
#include <tmfdem/base/parameters.h>
#include <vector>

namespace tmfdem
{
  /** What the user asked for on the command line. */
  struct CommandLine
  {
    enum class Action
    {
      run,
      help,
      print_parameters,
      validate
    };
    Action      action = Action::run;
    std::string prm_file;
    /** "Subsection/Entry=value" strings from --set, in order. */
    std::vector<std::string> overrides;
    /** --resume: continue from the newest checkpoint. */
    bool resume = false;
  };

  /** Parses argv; throws InputError for unknown options or missing files. */
  CommandLine
  parse_command_line(const int argc, const char *const *argv);

  /** The text of `tmfdem --help`. */
  std::string
  usage_text();

  /**
   * Reads @p prm_file, applies @p overrides, and parses everything into
   * Parameters. Any problem (unknown entry, malformed or out-of-range value,
   * unreadable file) becomes an InputError naming the file, line or entry.
   */
  Parameters
  read_parameters(const std::string              &prm_file,
                  const std::vector<std::string> &overrides);

  /** The complete, documented default parameter file. */
  std::string
  default_parameter_file();
} // namespace tmfdem

#endif
