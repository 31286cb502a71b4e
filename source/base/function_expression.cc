#include <deal.II/base/numbers.h>

#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>

namespace tmfdem
{
  namespace
  {
    /** Redirects std::cerr into a string while it lives (deal.II's
     *  FunctionParser prints muparser's error report there before it
     *  throws). */
    class CaptureStandardError
    {
    public:
      CaptureStandardError()
        : saved(std::cerr.rdbuf(captured.rdbuf()))
      {}
      ~CaptureStandardError()
      {
        std::cerr.rdbuf(saved);
      }
      std::string
      text() const
      {
        return captured.str();
      }

    private:
      std::ostringstream captured;
      std::streambuf    *saved;
    };

    /** The value of "Name: <value>" in muparser's report, or "". */
    std::string
    report_field(const std::string &report, const std::string &name)
    {
      const std::regex field(name + ":\\s*<([^\\n]*)>");
      std::smatch      match;
      if (std::regex_search(report, match, field))
        return match[1];
      return "";
    }

    /**
     * One message from muparser's report (captured from std::cerr) or,
     * without one, from deal.II's exception text: what is wrong and where
     * (1-based character, with a caret under the expression).
     */
    std::string
    describe_parse_error(const std::string &expression,
                         const std::string &report,
                         const std::string &exception_text)
    {
      std::string what = report_field(report, "Message");
      if (what.empty())
        {
          // deal.II: "... The parser said: <muparser message>"
          const std::string marker = "The parser said:";
          const auto        at     = exception_text.find(marker);
          what                     = at == std::string::npos ?
                                       exception_text :
                                       exception_text.substr(at + marker.size());
        }
      // muparser's own "at position N" counts from 0: replaced below
      what = std::regex_replace(what,
                                std::regex("\\s*(found )?at position \\d+\\.?"),
                                "");
      what = std::regex_replace(what, std::regex("^\\s+|\\s+$"), "");
      if (!what.empty())
        what[0] = static_cast<char>(std::tolower(what[0]));

      std::string       message       = what.empty() ? "syntax error" : what;
      const std::string position_text = report_field(report, "Position");
      if (!position_text.empty() &&
          std::regex_match(position_text, std::regex("\\d+")))
        {
          const std::size_t position =
            std::min<std::size_t>(std::stoul(position_text), expression.size());
          message += " at character " + std::to_string(position + 1) +
                     " of the expression\n    " + expression + "\n    " +
                     std::string(position, ' ') + "^";
        }
      return message;
    }
  } // namespace

  template <int dim>
  std::unique_ptr<dealii::FunctionParser<dim>>
  make_expression_function(const std::string &expression,
                           const std::string &entry_name)
  {
    auto function = std::make_unique<dealii::FunctionParser<dim>>(1);
    const std::map<std::string, double> constants = {
      {"pi", dealii::numbers::PI}};
    CaptureStandardError muparser_report;
    try
      {
        function->initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                             expression,
                             constants,
                             true);
        // muparser reports some errors only on the first evaluation
        function->value(dealii::Point<dim>());
      }
    catch (const dealii::ExceptionBase &exception)
      {
        std::ostringstream info;
        exception.print_info(info);
        throw InputError(
          "Entry '" + entry_name + "': cannot parse '" + expression +
          "' as a function of x [m], y [m], " + (dim == 3 ? "z [m], " : "") +
          "t [s] (muparser syntax, e.g. "
          "100*exp(-t/20)*sin(pi*x); pi is predefined): " +
          describe_parse_error(expression, muparser_report.text(), info.str()));
      }
    return function;
  }

  template std::unique_ptr<dealii::FunctionParser<2>>
  make_expression_function<2>(const std::string &, const std::string &);
  template std::unique_ptr<dealii::FunctionParser<3>>
  make_expression_function<3>(const std::string &, const std::string &);
} // namespace tmfdem
