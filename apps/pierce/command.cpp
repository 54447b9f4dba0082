#include "command.h"

#include <cctype>
#include <filesystem>

#include "pierce/error.h"

namespace pierce::cli {

Format format_of(const std::string& path) {
  if (path.empty()) return Format::none;
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".vtp") return Format::vtp;
  if (ext == ".csv") return Format::csv;
  if (ext == ".json") return Format::json;
  throw InputError(path + ": unknown output format (expected .vtp, .csv or .json)");
}

}  // namespace pierce::cli
