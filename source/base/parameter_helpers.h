/**
 * @file
 * Helpers of the parameter files of source/base/ (private to them): points
 * "x, y" and selections of registered names.
 */
#ifndef tmfdem_source_base_parameter_helpers_h
#define tmfdem_source_base_parameter_helpers_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <string>
#include <vector>

namespace tmfdem
{
  using namespace dealii;

  namespace parameter_helpers
  {
    /** "a, b" -> Point; the pattern has already checked the format. */
    inline Point<2>
    parse_point(const std::string &text)
    {
      const std::vector<double> values =
        Utilities::string_to_double(Utilities::split_string_list(text, ','));
      return Point<2>(values[0], values[1]);
    }

    /** "a|b|c" for Patterns::Selection. */
    inline std::string
    selection_of(const std::vector<std::string> &names)
    {
      std::string result;
      for (const auto &name : names)
        result += (result.empty() ? "" : "|") + name;
      return result;
    }

    /** The pattern of a point entry "x, y". */
    inline Patterns::List
    point_pattern()
    {
      return Patterns::List(Patterns::Double(), 2, 2, ",");
    }

    /** The pattern of a point entry "x, y" or "x, y, z" (entries that 3D
     *  runs read too). */
    inline Patterns::List
    space_point_pattern()
    {
      return Patterns::List(Patterns::Double(), 2, 3, ",");
    }

    /** "a, b" or "a, b, c" -> Point<3> (z = 0 when absent); the pattern
     *  has already checked the format. */
    inline Point<3>
    parse_space_point(const std::string &text)
    {
      const std::vector<double> values =
        Utilities::string_to_double(Utilities::split_string_list(text, ','));
      return Point<3>(values[0], values[1], values.size() > 2 ? values[2] : 0.);
    }
  } // namespace parameter_helpers
} // namespace tmfdem

#endif
