/**
 * @file
 * Prm entries whose values are functions of x [m], y [m] and t [s], parsed
 * with deal.II's FunctionParser (muparser syntax; `pi` is predefined).
 */
#ifndef tmfdem_base_function_expression_h
#define tmfdem_base_function_expression_h

#include <deal.II/base/function_parser.h>

#include <memory>
#include <string>

namespace tmfdem
{
  /**
   * Parses @p expression as a scalar function of x, y, t. On a syntax error
   * throws InputError naming @p entry_name (the prm path of the entry).
   */
  template <int dim = 2>
  std::unique_ptr<dealii::FunctionParser<dim>>
  make_expression_function(const std::string &expression,
                           const std::string &entry_name);
} // namespace tmfdem

#endif
