#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <bitset>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <tmfdem/base/command_line.h>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/simulation.h>

namespace tmfdem
{
  namespace
  {
    std::string
    exception_text(const ExceptionBase &exception)
    {
      std::ostringstream text;
      exception.print_info(text);
      std::string message = Utilities::trim(text.str());
      // deal.II words a few of its messages as addressed to a programmer
      const std::string prefix = "The violated condition was:";
      if (message.rfind(prefix, 0) == 0)
        message = message.substr(message.find('\n') + 1);
      // one line: collapse deal.II's indented multi-line layout
      std::string line;
      for (const char c : message)
        if (c == '\n' || c == '\t' || c == ' ')
          {
            if (!line.empty() && line.back() != ' ')
              line += ' ';
          }
        else
          line += c;
      return line;
    }

    /** Applies "A/B/Entry=value" to @p prm. */
    void
    apply_override(ParameterHandler &prm, const std::string &assignment)
    {
      const auto equals = assignment.find('=');
      if (equals == std::string::npos)
        throw InputError("--set '" + assignment +
                         "': expected \"Subsection/Entry=value\".");
      const std::string path  = Utilities::trim(assignment.substr(0, equals));
      const std::string value = Utilities::trim(assignment.substr(equals + 1));
      std::vector<std::string> parts;
      std::istringstream       in(path);
      for (std::string part; std::getline(in, part, '/');)
        parts.push_back(Utilities::trim(part));
      if (parts.empty() || parts.back().empty())
        throw InputError("--set '" + assignment + "': no entry name.");

      for (unsigned int i = 0; i + 1 < parts.size(); ++i)
        prm.enter_subsection(parts[i]);
      std::string error;
      try
        {
          prm.set(parts.back(), value);
        }
      catch (const ExceptionBase &exception)
        {
          error = exception_text(exception);
        }
      for (unsigned int i = 0; i + 1 < parts.size(); ++i)
        prm.leave_subsection();
      if (error.find("not yet declared") != std::string::npos)
        throw InputError("--set '" + assignment + "': there is no entry '" +
                         path +
                         "'. tmfdem --print-parameters lists all entries.");
      if (!error.empty())
        throw InputError("--set '" + assignment + "': " + error);
    }

    /**
     * FNV-1a 64 digest (hex) of the parameters that decide the results: all
     * entries, with those that do not (Checkpoint, Output/Directory,
     * Mesh/Gmsh time limit,
     * Output/Progress interval, Discrete mechanics/Threads and Allow
     * oversubscription: results do not depend on the thread count) reset to
     * fixed values first, and Time stepping/End time, which --resume may
     * extend to continue a run (checked against the checkpoint's time on
     * loading).
     */
    std::string
    input_digest(ParameterHandler &prm)
    {
      const std::vector<std::pair<std::vector<std::string>, std::string>>
        neutral = {{{"Checkpoint", "Interval (steps)"}, "0"},
                   {{"Checkpoint", "Interval (wall minutes)"}, "0"},
                   {{"Checkpoint", "Directory"}, ""},
                   {{"Checkpoint", "Keep"}, "2"},
                   {{"Output", "Directory"}, ""},
                   {{"Mesh", "Gmsh time limit"}, "300"},
                   {{"Output", "Progress interval"}, "2"},
                   {{"Discrete mechanics", "Threads"}, "1"},
                   {{"Discrete mechanics", "Allow oversubscription"}, "false"},
                   {{"Time stepping", "End time"}, "1"}};
      for (const auto &[path, value] : neutral)
        {
          for (unsigned int i = 0; i + 1 < path.size(); ++i)
            prm.enter_subsection(path[i]);
          prm.set(path.back(), value);
          for (unsigned int i = 0; i + 1 < path.size(); ++i)
            prm.leave_subsection();
        }
      std::ostringstream text;
      prm.print_parameters(text, ParameterHandler::ShortPRM);
      std::uint64_t hash = 1469598103934665603ull;
      for (const unsigned char c : text.str())
        {
          hash ^= c;
          hash *= 1099511628211ull;
        }
      std::ostringstream hex;
      hex << std::hex << std::setw(16) << std::setfill('0') << hash;
      return hex.str();
    }

    /**
     * The entries of @p prm whose value differs from the default, as
     * "Section/Subsection/Entry = value": the ShortPRM prints of @p prm and
     * of a default handler have the same lines in the same order (same
     * declarations), so a line that differs is an entry that was set.
     */
    std::vector<std::string>
    changed_entries(const ParameterHandler &prm)
    {
      ParameterHandler defaults;
      Parameters::declare_parameters(defaults);
      const auto lines = [](const ParameterHandler &handler) {
        std::ostringstream text;
        handler.print_parameters(text, ParameterHandler::ShortPRM);
        std::vector<std::string> result;
        std::istringstream       in(text.str());
        for (std::string line; std::getline(in, line);)
          result.push_back(Utilities::trim(line));
        return result;
      };
      const std::vector<std::string> set = lines(prm), unset = lines(defaults);
      std::vector<std::string>       changed, path;
      if (set.size() != unset.size())
        return changed; // cannot happen: same declarations
      for (std::size_t i = 0; i < set.size(); ++i)
        {
          const std::string &line = set[i];
          if (line.rfind("subsection ", 0) == 0)
            path.push_back(Utilities::trim(line.substr(11)));
          else if (line == "end" && !path.empty())
            path.pop_back();
          else if (line.rfind("set ", 0) == 0 && line != unset[i])
            {
              const auto  equals = line.find('=');
              std::string entry;
              for (const std::string &section : path)
                entry += section + "/";
              entry += Utilities::trim(line.substr(4, equals - 4)) + " = " +
                       Utilities::trim(line.substr(equals + 1));
              changed.push_back(entry);
            }
        }
      return changed;
    }

    /**
     * The `Materials/Material <id>` subsections the input defines: those
     * the prm file @p prm_file names (even empty) and those --set
     * @p overrides set an entry of. deal.II fills every declared subsection
     * with defaults, so only the text tells an absent material from one
     * given at its defaults. A .json or .xml input counts as defining all.
     */
    std::bitset<MaterialParameters::max_materials>
    materials_given(const std::string              &prm_file,
                    const std::vector<std::string> &overrides)
    {
      std::bitset<MaterialParameters::max_materials> given;
      const std::string                              extension =
        std::filesystem::path(prm_file).extension().string();
      if (extension == ".json" || extension == ".xml")
        return given.set();
      // "Material  2" and "Material 2" name the same subsection
      const auto normalised = [](const std::string &text) {
        std::string result;
        for (const char c : Utilities::trim(text))
          if (!(c == ' ' || c == '\t') ||
              (!result.empty() && result.back() != ' '))
            result += (c == '\t' ? ' ' : c);
        return result;
      };
      const auto mark = [&](const std::string &materials,
                            const std::string &material) {
        if (normalised(materials) != "Materials")
          return;
        const std::string name = normalised(material);
        for (unsigned int id = 0; id < given.size(); ++id)
          if (name == "Material " + std::to_string(id))
            given.set(id);
      };
      std::ifstream            in(prm_file);
      std::vector<std::string> path;
      for (std::string line; std::getline(in, line);)
        {
          const auto hash = line.find('#');
          if (hash != std::string::npos)
            line.erase(hash);
          line = normalised(line);
          if (line.rfind("subsection ", 0) == 0)
            {
              path.push_back(line.substr(11));
              if (path.size() == 2)
                mark(path[0], path[1]);
            }
          else if (line == "end" && !path.empty())
            path.pop_back();
        }
      for (const std::string &assignment : overrides)
        {
          std::vector<std::string> parts;
          std::istringstream text(assignment.substr(0, assignment.find('=')));
          for (std::string part; std::getline(text, part, '/');)
            parts.push_back(part);
          if (parts.size() >= 3)
            mark(parts[0], parts[1]);
        }
      return given;
    }
  } // namespace

  std::string
  usage_text()
  {
    return "tmfdem: thermo-mechanical simulation of rock that cracks "
           "(continuum deal.II solvers and combined finite-discrete "
           "elements)\n\n"
           "usage:\n"
           "  tmfdem case.prm [--set \"Subsection/Entry=value\" ...]   run a "
           "case\n"
           "  tmfdem case.prm --resume [--set ...]     continue from the "
           "newest checkpoint (Checkpoint subsection)\n"
           "  tmfdem --validate case.prm [--set ...]   check the input and the "
           "mesh, solve nothing\n"
           "  tmfdem --print-parameters                print the complete, "
           "documented default prm\n"
           "  tmfdem --help                            this text\n\n"
           "Outputs go to Output/Directory (default output/<prm stem>): "
           "solution.pvd, probes.csv, lines.csv, summary.json.\n"
           "Run in parallel with mpirun -np N tmfdem case.prm.\n"
           "Ctrl-C (SIGINT) or SIGTERM: the run finishes its step, writes its "
           "outputs and a checkpoint, and exits with status 3.\n"
           "Exit status: 0 success, 1 bad input, 2 failure during the run "
           "(also a guard: non-finite values, inverted elements, unstable "
           "step, runaway energy), 3 stopped by a signal.\n\n"
           "Models (prm entry Model):\n" +
           registered_simulation_descriptions() +
           "\nThe subsections each model reads (entries set elsewhere are "
           "reported as not read):\n" +
           registered_simulation_sections();
  }

  CommandLine
  parse_command_line(const int argc, const char *const *argv)
  {
    CommandLine command_line;
    for (int i = 1; i < argc; ++i)
      {
        const std::string argument = argv[i];
        if (argument == "--help" || argument == "-h")
          command_line.action = CommandLine::Action::help;
        else if (argument == "--print-parameters")
          command_line.action = CommandLine::Action::print_parameters;
        else if (argument == "--resume")
          command_line.resume = true;
        else if (argument == "--validate")
          command_line.action = CommandLine::Action::validate;
        else if (argument == "--set")
          {
            if (i + 1 >= argc)
              throw InputError("--set needs an argument "
                               "\"Subsection/Entry=value\".");
            command_line.overrides.emplace_back(argv[++i]);
          }
        else if (argument.rfind("--set=", 0) == 0)
          command_line.overrides.push_back(argument.substr(6));
        else if (!argument.empty() && argument[0] == '-')
          throw InputError("unknown option '" + argument +
                           "'; see tmfdem --help.");
        else if (command_line.prm_file.empty())
          command_line.prm_file = argument;
        else
          throw InputError("more than one parameter file given ('" +
                           command_line.prm_file + "' and '" + argument +
                           "').");
      }
    if ((command_line.action == CommandLine::Action::run ||
         command_line.action == CommandLine::Action::validate) &&
        command_line.prm_file.empty())
      {
        if (argc == 1)
          command_line.action = CommandLine::Action::help;
        else
          throw InputError("no parameter file given; see tmfdem --help.");
      }
    return command_line;
  }

  Parameters
  read_parameters(const std::string              &prm_file,
                  const std::vector<std::string> &overrides)
  {
    {
      std::ifstream probe(prm_file);
      if (!probe)
        throw InputError("cannot open the parameter file '" + prm_file +
                         "' (missing or unreadable).");
      // deal.II's `include` recurses without a depth limit (a file that
      // includes itself overflows the stack): tmfdem files are flat
      std::string  line;
      unsigned int number = 0;
      while (std::getline(probe, line))
        {
          ++number;
          const auto first = line.find_first_not_of(" \t");
          if (first != std::string::npos &&
              line.compare(first, 7, "include") == 0 &&
              (line.size() == first + 7 || line[first + 7] == ' ' ||
               line[first + 7] == '\t'))
            throw InputError("in parameter file '" + prm_file + "', line " +
                             std::to_string(number) +
                             ": 'include' is not allowed; write the entries "
                             "into the file (or use --set).");
        }
    }
    {
      // an empty file would run the built-in default case
      std::ifstream probe(prm_file);
      bool          sets = !overrides.empty();
      for (std::string line; !sets && std::getline(probe, line);)
        {
          const std::string text = Utilities::trim(line);
          sets = text.rfind("set ", 0) == 0 || text.rfind("set\t", 0) == 0;
        }
      if (!sets)
        throw InputError(
          "parameter file '" + prm_file +
          "' sets no entries (it is empty or holds only comments or empty "
          "subsections); tmfdem does not run a built-in default case. Needed "
          "are at least 'set Model = ...' (one of: " +
          [] {
            std::string names;
            for (const std::string &name : registered_simulation_names())
              names += (names.empty() ? "" : ", ") + name;
            return names;
          }() +
          "), the Mesh, a subsection Materials/Material <id> for each "
          "material id of the mesh, Time stepping and the boundary "
          "conditions of the case. prm/*.prm are complete examples; tmfdem "
          "--print-parameters prints every entry with its documentation.");
    }
    ParameterHandler prm;
    Parameters::declare_parameters(prm);
    try
      {
        prm.parse_input(prm_file, "", false, false);
      }
    catch (const ExceptionBase &exception)
      {
        throw InputError("in parameter file '" + prm_file +
                         "': " + exception_text(exception));
      }
    for (const auto &assignment : overrides)
      apply_override(prm, assignment);
    Parameters parameters;
    parameters.prm_file        = prm_file;
    parameters.materials.given = materials_given(prm_file, overrides);
    try
      {
        parameters.parse_parameters(prm);
      }
    catch (const InputError &error)
      {
        throw InputError("in parameter file '" + prm_file +
                         "': " + error.what());
      }
    catch (const ExceptionBase &exception)
      {
        throw InputError("in parameter file '" + prm_file +
                         "': " + exception_text(exception));
      }
    parameters.changed_entries = changed_entries(prm);
    parameters.input_digest    = input_digest(prm);
    return parameters;
  }

  std::string
  default_parameter_file()
  {
    ParameterHandler prm;
    Parameters::declare_parameters(prm);
    std::ostringstream text;
    text << "# tmfdem: complete default parameter file "
            "(tmfdem --print-parameters)\n"
            "# Units are SI; temperatures in degrees C. Functions of x, y, t "
            "use muparser syntax.\n"
            "# The subsections each model reads (entries set elsewhere are "
            "reported as not read):\n";
    {
      std::istringstream models(registered_simulation_sections());
      for (std::string line; std::getline(models, line);)
        text << "#" << line << "\n";
    }
    prm.print_parameters(text,
                         ParameterHandler::OutputStyle(
                           ParameterHandler::PRM |
                           ParameterHandler::KeepDeclarationOrder));
    return text.str();
  }
} // namespace tmfdem
