#include "pierce/solid_reference.h"

#include <algorithm>

namespace pierce {

std::optional<std::uint32_t> parse_solid_id(std::string_view text) {
  if (!text.empty() && text.front() == '#') text.remove_prefix(1);
  if (text.empty() || text.size() > 9) return std::nullopt;  // 9 digits cannot overflow 32 bits
  std::uint32_t id = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    id = id * 10 + std::uint32_t(c - '0');
  }
  return id;
}

std::vector<std::uint32_t> find_solids(const Scene& scene, std::string_view reference) {
  std::vector<std::uint32_t> ids;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
    if (scene.geometry(g).name == reference) ids.push_back(g);
  if (!ids.empty()) return ids;
  if (const std::optional<std::uint32_t> id = parse_solid_id(reference); id && *id < scene.geometries().size())
    ids.push_back(*id);
  return ids;
}

std::string known_solid_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const Geometry& g : scene.geometries()) names.push_back(g.name.empty() ? "(unnamed)" : g.name);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  if (names.empty()) return "none: the scene is empty";
  constexpr std::size_t kShown = 20;
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < kShown; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > kShown) s += ", ... (" + std::to_string(names.size() - kShown) + " more)";
  return s + "; or #N for geometry id N < " + std::to_string(scene.geometries().size());
}

}  // namespace pierce
