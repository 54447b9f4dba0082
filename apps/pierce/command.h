#pragma once
// Each `pierce` subcommand lives in its own cmd_*.cpp and registers itself here; this header also
// brings what every subcommand shares: Ctrl-C and cancelled() (interrupt.h), progress bars
// (progress.h) and the output format named by a file's extension.
#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>

#include "interrupt.h"
#include "model_args.h"
#include "output_file.h"
#include "pierce/kernel.h"
#include "progress.h"

namespace pierce::cli {

// Output formats of the analyses' -o FILE, from the extension (case-insensitive); none for an
// empty path. Throws InputError naming the file for any other extension.
enum class Format { none, vtp, csv, json };
Format format_of(const std::string& path);

// Options that every analysis takes, worded once: --kernel (an exact kernel, `kernel` holding its
// default), and --force (overwrite `outputs`, e.g. "an existing output file") with --progress.
void add_exact_kernel_option(CLI::App* cmd, std::string& kernel);
void add_force_and_progress_flags(CLI::App* cmd, bool& force, bool& progress, const std::string& outputs);

// The exact kernel `name` names (--kernel of the analyses); throws InputError "--kernel 'x': not
// an exact kernel" for an unknown or inexact one.
KernelKind exact_kernel_option(const std::string& name);

// Writes `path` (stdout when empty) through write(stream); the file appears only when complete
// and not after Ctrl-C. Returns the command's exit code (0, or kExitCancelled).
template <class Write>
int write_file(const std::string& path, bool force, Write write) {
  OutputFile out(path, force);
  write(out.stream());
  if (interrupted()) return cancelled();
  out.commit();
  return 0;
}

// Writes -o FILE (format != none) through write(format, stream), as write_file does.
template <class Write>
int write_output(const std::string& path, Format format, bool force, Write write) {
  if (format == Format::none) return 0;
  return write_file(path, force, [&](std::FILE* out) { write(format, out); });
}

// The command line `pierce` was started with (main records it), each argument quoted for a POSIX
// shell where it needs quoting: what a report says it was made by.
void record_command_line(int argc, char** argv);
const std::string& command_line();

// The text reports of `shot` and `classify`: throws InputError unless --format names one of
// table, csv or json.
void check_report_format(const std::string& format);

// A subcommand being declared: the options its flags fill (shared with the callback that runs it)
// and the CLI11 node the flags are added to.
template <class Options>
struct NewCommand {
  std::shared_ptr<Options> options;
  CLI::App* cmd;
};

// Adds subcommand `name` with a fresh, default Options.
template <class Options>
NewCommand<Options> add_command(CLI::App& app, const std::string& name, const std::string& description) {
  return {std::make_shared<Options>(), app.add_subcommand(name, description)};
}

// Adds subcommand `name` that reads models: the positional MODEL argument(s) (more than one when
// `several`) and the tessellation options, into Options::model (add_model_args).
template <class Options>
NewCommand<Options> add_model_command(CLI::App& app, const std::string& name, const std::string& description,
                                      bool several = true) {
  NewCommand<Options> c = add_command<Options>(app, name, description);
  add_model_args(c.cmd, c.options->model, several);
  return c;
}

// Each returns the callback that runs the subcommand (after parsing) and returns its exit code.
std::function<int()> register_hits(CLI::App& app);
std::function<int()> register_info(CLI::App& app);
std::function<int()> register_thickness(CLI::App& app);
std::function<int()> register_overlaps(CLI::App& app);
std::function<int()> register_shot(CLI::App& app);
std::function<int()> register_gqa(CLI::App& app);
std::function<int()> register_run(CLI::App& app);
std::function<int()> register_classify(CLI::App& app);
std::function<int()> register_report(CLI::App& app);

}  // namespace pierce::cli
