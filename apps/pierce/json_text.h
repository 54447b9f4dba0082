#pragma once
// JSON pieces shared by the CLI's --json and .json writers.
#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "pierce/vec3.h"

namespace pierce::cli {

// A point as [x, y, z].
inline nlohmann::ordered_json json_point(Vec3d p) { return {p.x, p.y, p.z}; }

// `v`, or null where it is missing (NaN). (nlohmann writes an infinity as null too.)
inline nlohmann::ordered_json json_or_null(double v) {
  return std::isnan(v) ? nlohmann::ordered_json() : nlohmann::ordered_json(v);
}

// The document `j` to `f`, indented by one space, with a final newline.
inline void write_json_document(std::FILE* f, const nlohmann::ordered_json& j) {
  const std::string text = j.dump(1);
  std::fwrite(text.data(), 1, text.size(), f);
  std::fputc('\n', f);
}

}  // namespace pierce::cli
