// commands.hpp: the subcommands of harris-cosim. Each lives in its own cmd_*.cpp and adds
// itself to the app with add_X_command; its callback parses nothing itself beyond its flags,
// calls a library through its typed API and prints. A failure is an exception of the kind
// io/util/errors.hpp lists (MismatchError, InputError, SimulatorError, TranslationFault,
// InternalError); main (harris_cosim.cpp) maps each kind to its exit status.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <utility>

namespace hc::tools {

/// A flag check for whole numbers >= `min` whose message is short ("--frames: '-1' is not a
/// whole number >= 0"); CLI11's NonNegativeNumber and PositiveNumber print their bound as a
/// 300-digit double.
inline CLI::Validator whole_number(long min) {
    return CLI::Validator(
        [min](std::string& s) -> std::string {
            std::size_t used = 0;
            long v = 0;
            try {
                v = std::stol(s, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (s.empty() || used != s.size() || v < min)
                return "'" + s + "' is not a whole number >= " + std::to_string(min);
            return {};
        },
        "N >= " + std::to_string(min));
}

/// A subcommand `name` of `app` with its help, and the options its flags fill, which its
/// callback shares.
template <class Options>
std::pair<CLI::App*, std::shared_ptr<Options>> add_command(CLI::App& app, const std::string& name, const std::string& help) {
    return {app.add_subcommand(name, help), std::make_shared<Options>()};
}

void add_rtl_command(CLI::App& app);        // GHDL co-simulation (cmd_rtl.cpp)
void add_model_command(CLI::App& app);      // cycle model alone (cmd_rtl.cpp)
void add_golden_command(CLI::App& app);     // golden reference files (cmd_golden.cpp)
void add_mutate_command(CLI::App& app);     // mutation campaign (cmd_mutate.cpp)
void add_verilate_command(CLI::App& app);   // Verilator full-frame verification (cmd_verilate.cpp)
void add_eval_command(CLI::App& app);       // precision/recall against OpenCV (cmd_eval.cpp)
void add_sweep_command(CLI::App& app);      // bit-width exploration (cmd_sweep.cpp)
void add_ranges_command(CLI::App& app);     // derived ranges of the registers (cmd_ranges.cpp)
void add_calibrate_command(CLI::App& app);  // stereo calibration of a rig (cmd_calibrate.cpp)
void add_slam_command(CLI::App& app);       // 2-D EKF-SLAM (cmd_slam.cpp)
void add_landmarks_command(CLI::App& app);  // descriptors, stereo matches, landmarks (cmd_landmarks.cpp)
void add_shard_command(CLI::App& app);      // worker and merge ends of sharded runs (cmd_shard.cpp)

}  // namespace hc::tools
