// `pierce`: command-line front end; one cmd_*.cpp per subcommand (command.h).
#include <iostream>
#include <vector>

#include "command.h"
#include "pierce/error.h"
#include "pierce/version.h"

int main(int argc, char** argv) {
  pierce::cli::record_command_line(argc, argv);
  CLI::App app{"Pierce: exact multi-hit ray traversal"};
  app.set_version_flag("--version", "pierce " PIERCE_VERSION_STRING, "Print the version and exit");
  app.require_subcommand(1);
  std::vector<std::pair<CLI::App*, std::function<int()>>> commands;
  for (auto reg : {pierce::cli::register_hits, pierce::cli::register_info, pierce::cli::register_thickness,
                   pierce::cli::register_overlaps, pierce::cli::register_shot, pierce::cli::register_gqa,
                   pierce::cli::register_run, pierce::cli::register_classify,
                   pierce::cli::register_report}) {
    const std::size_t before = app.get_subcommands({}).size();
    auto run = reg(app);
    commands.emplace_back(app.get_subcommands({})[before], std::move(run));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (auto& [sub, run] : commands)
      if (sub->parsed()) return run();
  } catch (const pierce::InputError& e) {
    std::cerr << "pierce: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pierce: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
