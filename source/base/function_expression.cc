#include <deal.II/base/numbers.h>

#include <map>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>

namespace tmfdem
{
  std::unique_ptr<dealii::FunctionParser<2>>
  make_expression_function(const std::string &expression,
                           const std::string &entry_name)
  {
    auto function = std::make_unique<dealii::FunctionParser<2>>(1);
    const std::map<std::string, double> constants = {
      {"pi", dealii::numbers::PI}};
    try
      {
        function->initialize("x,y,t", expression, constants, true);
        // muparser reports some errors only on the first evaluation
        function->value(dealii::Point<2>(0., 0.));
      }
    catch (const dealii::ExceptionBase &exception)
      {
        std::ostringstream info;
        exception.print_info(info);
        throw InputError("Entry '" + entry_name + "': cannot parse '" +
                         expression +
                         "' as a function of x, y, t: " + info.str());
      }
    return function;
  }
} // namespace tmfdem
