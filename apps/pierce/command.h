#pragma once
// Each `pierce` subcommand lives in its own cmd_*.cpp and registers itself here.
#include <CLI/CLI.hpp>

#include <functional>

namespace pierce::cli {

// Adds the subcommand to `app`; the returned callback runs it and returns the exit code.
using Register = std::function<std::function<int()>(CLI::App& app)>;

std::function<int()> register_hits(CLI::App& app);
std::function<int()> register_info(CLI::App& app);
std::function<int()> register_thickness(CLI::App& app);
std::function<int()> register_overlaps(CLI::App& app);
std::function<int()> register_shot(CLI::App& app);
std::function<int()> register_gqa(CLI::App& app);
std::function<int()> register_run(CLI::App& app);
std::function<int()> register_classify(CLI::App& app);

}  // namespace pierce::cli
