// commands.hpp: the subcommands of harris-cosim and the flags they share. Each command lives in
// its own cmd_*.cpp: it binds its flags to its library's command settings and calls that
// library's run function once; every check, file and printed figure is the library's. A
// failure is an exception of the kind model/util/errors.hpp lists; main (harris_cosim.cpp) maps
// each kind to its exit status.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <utility>

#include "io/cluster/runner.hpp"
#include "io/frames/frames.hpp"

namespace hc::tools {

/// A flag check for whole numbers >= `min` whose message is short ("--frames: '-1' is not a
/// whole number >= 0"); CLI11's NonNegativeNumber and PositiveNumber print their bound as a
/// 300-digit double.
CLI::Validator whole_number(long min);

/// A subcommand `name` of `app` with its help, and the settings its flags fill, which its
/// callback shares. The subcommand owns them (its pre-parse callback, which does nothing, holds
/// them), so they live as long as the flags that write into them, whatever its callback becomes.
template <class Settings>
std::pair<CLI::App*, std::shared_ptr<Settings>> add_command(CLI::App& app, const std::string& name, const std::string& help) {
    auto settings = std::make_shared<Settings>();
    CLI::App* cmd = app.add_subcommand(name, help);
    cmd->preparse_callback([settings](std::size_t) {});
    return {cmd, settings};
}

/// A command's settings with the sharding flags' values beside them.
template <class Command>
struct Sharded : Command {
    cluster::RunnerSettings runner;
};

/// The frame-source flags of every command that streams images, bound to `o`: image files,
/// globs, folders or a video (positional), --pattern, --size, --frames N, --kitti,
/// --sequence, --pairs a:b, --data, --seed. --frames N counts frames (the first N of any
/// stream), --pairs a:b picks stereo pairs, in every command.
void add_frame_source_options(CLI::App* cmd, frames::FrameSource& o);

/// `--pairs a:b`, a range of a stereo dataset's pairs (b excluded; util::parse_range's syntax,
/// checked when parsed), bound to `range`: the one help text of every command's --pairs, with
/// `more` (a command's own default or use) appended.
void add_pair_range_option(CLI::App* cmd, std::string& range, const std::string& more = {});

/// A user's rig, bound to `r` (frames::RigSource): --calib FILE, --left and --right (image
/// files, quoted glob patterns or folders, paired in order): the one help text of every command
/// that reads a rig, with `use` (what the command does with it) appended to --calib's.
void add_rig_options(CLI::App* cmd, frames::RigSource& r, const std::string& use);

/// The sharding flags (in an option group "Sharding"), bound to `s`.
void add_runner_flags(CLI::App* cmd, cluster::RunnerSettings& s);

/// The runner of a command, with every job kind of the executable. The one sharding rule:
/// a command runs in shards when one of cluster::kShardingFlags is given on `cmd`, in one
/// process otherwise. --jobs is how many processes run at once: a sharded run's shards, or
/// those a command's single run starts itself (`single_jobs`: the sweep's syntheses and GHDL
/// runs, the generated campaign's pool). A command whose single run starts none refuses
/// --jobs without a sharding flag (InputError), so that no flag is silently ignored.
cluster::JobRunner job_runner(const CLI::App* cmd, cluster::RunnerSettings s, bool single_jobs = false);

/// The path of this executable (main's argv[0], resolved), the runner's worker program.
void set_program_path(const char* argv0);
/// The command line as typed, for the reports: set_command_line keeps argv[1..];
/// typed_command_line gives `harris-cosim` and them, shell-quoted, less the sharding flags of
/// `cmd` (the "Sharding" group of add_runner_flags: they say where the work runs, not what it
/// computes, so a report made in shards equals the one made in one process byte for byte).
void set_command_line(int argc, char** argv);
std::string typed_command_line(const CLI::App* cmd);
/// Every flag of `cmd` but the sharding flags and --help, one `name=value` a line in the order
/// of its options: the value given (several joined by spaces), else its default ("" where it has
/// none; a flag without a value: true or false). What a report records of its settings.
std::string effective_settings(const CLI::App* cmd);

/// The run of a command whose reports quote its command line: `o.command_line` =
/// typed_command_line(cmd), then `run(o, job_runner(cmd, o.runner, single_jobs))`.
template <class Settings, class Run>
void run_quoting_command_line(const CLI::App* cmd, Settings& o, Run run, bool single_jobs = false) {
    o.command_line = typed_command_line(cmd);
    run(o, job_runner(cmd, o.runner, single_jobs));
}

void add_rtl_command(CLI::App& app);        // GHDL co-simulation (cmd_rtl.cpp)
void add_model_command(CLI::App& app);      // cycle model alone (cmd_rtl.cpp)
void add_golden_command(CLI::App& app);     // golden reference files (cmd_golden.cpp)
void add_mutate_command(CLI::App& app);     // mutation campaigns (cmd_mutate.cpp)
void add_verilate_command(CLI::App& app);   // Verilator full-frame verification (cmd_verilate.cpp)
void add_eval_command(CLI::App& app);       // precision/recall against OpenCV (cmd_eval.cpp)
void add_sweep_command(CLI::App& app);      // bit-width exploration (cmd_sweep.cpp)
void add_ranges_command(CLI::App& app);     // derived ranges of the registers (cmd_ranges.cpp)
void add_calibrate_command(CLI::App& app);  // stereo calibration of a rig (cmd_calibrate.cpp)
void add_slam_command(CLI::App& app);       // 2-D EKF-SLAM (cmd_slam.cpp)
void add_landmarks_command(CLI::App& app);  // descriptors, stereo matches, landmarks (cmd_landmarks.cpp)
void add_shard_command(CLI::App& app);      // worker and merge ends of sharded runs (cmd_shard.cpp)
/// Every command above, added to `app` in the order --help lists them.
void add_commands(CLI::App& app);

}  // namespace hc::tools
