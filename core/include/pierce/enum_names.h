#pragma once
// Names of option enums, written once: every front end (CLI, Python, VTK, FreeCAD) maps user text
// to an enum through these tables, so the spellings and the error message are the same
// everywhere. An enum opts in with an `enum_table` function beside it, found by argument-dependent
// lookup:
//   constexpr EnumTable<Colour, 2> enum_table(Colour) {
//     using enum Colour;
//     return {"colour", {{red, "red"}, {blue, "blue"}}};
//   }
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pierce {

template <class E>
struct NamedValue {
  E value;
  std::string_view name;
};

// `what` names the option in messages; `values` are in the order front ends list them.
template <class E, std::size_t N>
struct EnumTable {
  std::string_view what;
  NamedValue<E> values[N];
};

// E's table, evaluated once at compile time.
template <class E>
inline constexpr auto kEnumTable = enum_table(E{});

template <class E>
std::string_view enum_name(E v) {
  for (const NamedValue<E>& n : kEnumTable<E>.values)
    if (n.value == v) return n.name;
  return "?";
}

template <class E>
std::optional<E> parse_enum(std::string_view name) {
  for (const NamedValue<E>& n : kEnumTable<E>.values)
    if (n.name == name) return n.value;
  return std::nullopt;
}

// Every name, in table order (e.g. for a CLI's list of allowed values).
template <class E>
std::vector<std::string> enum_names() {
  std::vector<std::string> out;
  for (const NamedValue<E>& n : kEnumTable<E>.values) out.emplace_back(n.name);
  return out;
}

// "a, b, c"
template <class E>
std::string enum_name_list() {
  std::string s;
  for (const NamedValue<E>& n : kEnumTable<E>.values) s += (s.empty() ? "" : ", ") + std::string(n.name);
  return s;
}

// The value named `name`; throws std::invalid_argument "unknown <what> 'x' (expected one of: a, b)"
// (Python's bindings raise it as ValueError).
template <class E>
E parse_enum_or_throw(std::string_view name) {
  if (const std::optional<E> v = parse_enum<E>(name)) return *v;
  throw std::invalid_argument("unknown " + std::string(kEnumTable<E>.what) + " '" + std::string(name) +
                              "' (expected one of: " + enum_name_list<E>() + ")");
}

}  // namespace pierce
