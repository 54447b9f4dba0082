#pragma once
// How a user names solids, the same in every front end (`pierce thickness --solid`, CSG
// expressions, the `solids` of a `pierce run` scene file): by name (every geometry carrying it),
// or by geometry id written `#N` or a bare `N`. A name that some geometry carries wins over the id
// reading of the same text; the one exception is `#N` written unquoted in a CSG expression, which
// is always an id (a solid literally named "#3" is written in quotes there).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pierce/scene.h"

namespace pierce {

// "#12" or "12" -> 12; anything else (signs, blanks, more than 9 digits) -> nullopt.
std::optional<std::uint32_t> parse_solid_id(std::string_view text);

// The geometries `reference` names, ascending: those carrying the name; if none does, the
// geometry whose id it gives (parse_solid_id) when it exists; else none.
std::vector<std::uint32_t> find_solids(const Scene& scene, std::string_view reference);

// The scene's solid names for "unknown solid" messages: "a, b, c; or #N for geometry id N < 3"
// (at most 20 names, sorted, unnamed geometries as "(unnamed)").
std::string known_solid_names(const Scene& scene);

}  // namespace pierce
