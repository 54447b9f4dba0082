#pragma once
// The filters' integer enum properties (vtkPierceThickness::RAY, ..., and the EnumerationDomain
// entries of the ParaView XML) are positions in core's name tables (pierce/enum_names.h), so that
// values and names have one source: a code maps to core's enum and name by position, and a name
// is parsed by core (with core's error listing the valid names).
#include <cstddef>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

#include "pierce/enum_names.h"

namespace pierce_vtk {

// The value at `code` in E's table; throws std::invalid_argument outside it.
template <class E>
constexpr E EnumAt(int code)
{
  constexpr auto& values = pierce::kEnumTable<E>.values;
  if (code < 0 || static_cast<std::size_t>(code) >= std::size(values))
  {
    throw std::invalid_argument(
      "no " + std::string(pierce::kEnumTable<E>.what) + " number " + std::to_string(code));
  }
  return values[code].value;
}

// True when `code` is the position of `value` in E's table (for static_asserts on the codes).
template <class E>
constexpr bool IsCodeOf(int code, E value)
{
  return EnumAt<E>(code) == value;
}

// The core name of the value at `code` ("?" outside the table).
template <class E>
const char* EnumNameAt(int code)
{
  constexpr auto& values = pierce::kEnumTable<E>.values;
  if (code < 0 || static_cast<std::size_t>(code) >= std::size(values))
  {
    return "?";
  }
  return values[code].name.data(); // the tables' names are string literals
}

// The code of the value named `name`; throws std::invalid_argument naming the valid names.
template <class E>
int EnumCodeOf(std::string_view name)
{
  const E value = pierce::parse_enum_or_throw<E>(name);
  constexpr auto& values = pierce::kEnumTable<E>.values;
  for (std::size_t i = 0; i < std::size(values); ++i)
  {
    if (values[i].value == value)
    {
      return static_cast<int>(i);
    }
  }
  return -1; // not reached: parse_enum_or_throw found it in the table
}

} // namespace pierce_vtk
