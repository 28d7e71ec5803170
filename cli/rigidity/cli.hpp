#pragma once
/// The rigidity command line (docs/cli.md):
///
///   rigidity run [SCENE.yaml] [--out DIR] [--set key.path=value ...] [--quiet]
///   rigidity validate SCENE.yaml [--set key.path=value ...]
///   rigidity materials [NAME] [--json]
///   rigidity compare [--materials a,b,...] [--out DIR] [--speeds v1,v2,...] [--impact-speed v]
///                    [--param model.name=value ...]
///   rigidity plot RUN_DIR [--out DIR]
///
/// Exit status: 0 done, 1 internal failure or a run stopped by a budget, 2 invalid input,
/// 3 physically inadmissible, 130 a run interrupted by Ctrl-C (143 by SIGTERM).
/// This header is private to the executable.

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rigidity {

/// Runs the command line; returns the exit status. Never throws.
int cli_main(int argc, char** argv);

namespace cli {

/// A failure the command reports as "error: what()" with its own exit status;
/// a usage error also prints the command's usage line.
class CommandError : public std::runtime_error {
 public:
  CommandError(int exit_status, const std::string& message, bool show_usage = false, std::string command = {})
      : std::runtime_error(message), exit_status_(exit_status), show_usage_(show_usage), command_(std::move(command)) {}
  [[nodiscard]] int exit_status() const noexcept { return exit_status_; }
  [[nodiscard]] bool show_usage() const noexcept { return show_usage_; }
  /// The command whose usage applies ("" for the top level).
  [[nodiscard]] const std::string& command() const noexcept { return command_; }

 private:
  int exit_status_;
  bool show_usage_;
  std::string command_;
};

/// An invalid command line: exit 2 with the usage.
[[nodiscard]] CommandError usage_error(const std::string& command, const std::string& message);

struct OptionSpec {
  std::string_view name;  ///< "--out"
  bool takes_value = false;
  bool repeatable = false;
};

/// A command's arguments after parsing.
struct Arguments {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::string>> options;  ///< in order; flags have an empty value
  bool help = false;

  [[nodiscard]] bool has(std::string_view option) const;
  /// The value of a non-repeatable option, if given.
  [[nodiscard]] std::optional<std::string> value(std::string_view option) const;
  /// Every value of a repeatable option, in order.
  [[nodiscard]] std::vector<std::string> values(std::string_view option) const;
};

/// Parses `args` (after the command name) against `options`; `--help`/`-h` is always
/// accepted, `--` ends the options. \throws CommandError (usage) on an unknown option,
/// naming the closest one, or a missing value.
[[nodiscard]] Arguments parse_arguments(const std::string& command, std::span<const std::string> args,
                                        std::span<const OptionSpec> options);

/// The `--set key.path=value` overrides, checked for their form.
/// \throws CommandError (usage) on a value without '=' or without a key
[[nodiscard]] std::vector<std::string> scene_overrides(const Arguments& args, const std::string& command);

/// `text` (an argument or a CSV cell) as a finite number, or nullopt.
[[nodiscard]] std::optional<double> parse_number(const std::string& text);

/// The usage line(s) of a command ("" → every command).
[[nodiscard]] std::string usage(std::string_view command);
/// The full help text of a command ("" → the program).
[[nodiscard]] std::string help(std::string_view command);

// The commands. Each returns the exit status or throws (mapped to one by cli_main).
int run_command(std::span<const std::string> args, std::ostream& out);
int validate_command(std::span<const std::string> args, std::ostream& out);
int materials_command(std::span<const std::string> args, std::ostream& out);
int compare_command(std::span<const std::string> args, std::ostream& out);
int plot_command(std::span<const std::string> args, std::ostream& out);
int schema_command(std::span<const std::string> args, std::ostream& out);
int sweep_command(std::span<const std::string> args, std::ostream& out);

/// While in scope, SIGINT (Ctrl-C) and SIGTERM (kill, timeout, a batch system's time
/// limit) ask the running solve or sweep to stop cleanly (request_interrupt): its outputs up
/// to then are written, with status interrupted, and no temporary directory is left
/// behind. The first signal writes a notice on stderr (unless quiet). A repeated SIGTERM,
/// and a SIGINT within kGraceNs of the first signal, are the same request (GNU timeout
/// signals the program and then its process group); a Ctrl-C after that ends the process at
/// once, by SIGINT, without its outputs. After a signal the handler stays installed to the
/// end of the process. Shared by `run` and `sweep`.
class StopOnSignals {
 public:
  /// How long after the first signal a SIGINT is still taken as the same request [ns].
  static constexpr std::int64_t kGraceNs = 500'000'000;

  explicit StopOnSignals(bool quiet = false);
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;
  /// The exit status of a run those signals stopped: 130 for Ctrl-C, 143 for SIGTERM.
  [[nodiscard]] static int exit_status();
  /// "Ctrl-C" or "SIGTERM", for the message.
  [[nodiscard]] static const char* cause();

 private:
  static constexpr int kSignals[2] = {SIGINT, SIGTERM};
  struct sigaction previous_[2]{};
  bool installed_[2] = {false, false};
};

// gnuplot, shared by `compare` and `plot` (defined in plot_command.cpp).

/// The gnuplot executable found on PATH, or an empty path if there is none.
[[nodiscard]] std::filesystem::path find_gnuplot();
/// Writes `script` to dir/NAME.gp (kept, so that users can tweak and rerun it) and runs
/// `gnuplot NAME.gp` in dir, which is expected to write dir/NAME.IMAGE (png, or gif).
/// \throws CommandError (exit 1) with gnuplot's messages if it fails or writes no image
void render_gnuplot(const std::filesystem::path& gnuplot, const std::filesystem::path& dir, const std::string& name,
                    const std::string& script, std::string_view image = "png");
/// `text` as a single-quoted gnuplot string literal.
[[nodiscard]] std::string gnuplot_quote(std::string_view text);
/// `text` as gnuplot comment lines ("# ..."), wrapped at word boundaries.
[[nodiscard]] std::string gnuplot_comment(std::string_view text);

}  // namespace cli
}  // namespace rigidity
