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

void add_exact_kernel_option(CLI::App* cmd, std::string& kernel) {
  cmd->add_option("--kernel", kernel, "Exact kernel to trace with (all give the same result)")->capture_default_str();
}

void add_force_and_progress_flags(CLI::App* cmd, bool& force, bool& progress, const std::string& outputs) {
  cmd->add_flag("--force", force, "Overwrite " + outputs);
  cmd->add_flag("--progress", progress, "Show a progress bar on stderr even when it is not a terminal");
}

KernelKind exact_kernel_option(const std::string& name) {
  const std::optional<KernelKind> kernel = parse_kernel(name);
  if (!kernel || !is_exact(*kernel)) throw InputError("--kernel '" + name + "': not an exact kernel");
  return *kernel;
}

namespace {
std::string& recorded_command_line() {
  static std::string line;
  return line;
}
}  // namespace

void record_command_line(int argc, char** argv) {
  std::string& line = recorded_command_line();
  line.clear();
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (i) line += ' ';
    const bool plain = !a.empty() && a.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
                                                         "_-+=,.:/@%#") == std::string::npos;
    if (plain) {
      line += a;
      continue;
    }
    line += '\'';
    for (char c : a) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += '\'';
  }
}

const std::string& command_line() { return recorded_command_line(); }

void check_report_format(const std::string& format) {
  if (format != "table" && format != "csv" && format != "json")
    throw InputError("--format '" + format + "': expected table, csv or json");
}

}  // namespace pierce::cli
