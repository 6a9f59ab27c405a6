// mutated_run.hpp: the run both campaigns make of a mutant. rtl/ is copied into a scratch
// folder, one file of the copy is edited, the copy is analysed with GHDL's mcode back end
// and co-simulated (cosim::run_ghdl) against the unmutated cycle model, stream after stream.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cosim/cosim.hpp"

namespace hc::mutation {

/// One edit of one rtl/ file: the file's name, what its text becomes, and how errors name it.
struct FileEdit {
    std::string file;                                        ///< "sobel_x.vhd"
    std::function<std::string(const std::string&)> apply;    ///< may throw InputError
    std::string what;                                        ///< "rtl/sobel_x.vhd (mutation M3)"
};

/// A copy of rtl/'s sources in `dir`/rtl with `e` applied (nullptr: unmutated); its path.
std::filesystem::path mutated_copy(const FileEdit* e, const std::filesystem::path& dir);

/// What one co-simulation of the mutated copy found.
struct StreamOutcome {
    std::optional<cosim::GhdlResult> result;   ///< empty when the simulator failed
    std::string error;                         ///< the SimulatorError's message, when it failed
    std::filesystem::path log;                 ///< the simulator's output
    double seconds = 0;
};

struct MutatedRun {
    bool analysed = false;
    std::filesystem::path analyse_log;
    double analyse_seconds = 0;
    std::vector<StreamOutcome> streams;        ///< the streams co-simulated, in order
};

/// The next stream to co-simulate, given what the run found so far (nullopt: stop there).
using NextStream = std::function<std::optional<cosim::GhdlRun>(const MutatedRun& so_far)>;

/// Empties `work`, makes the mutated copy there (mutated_copy), analyses it with GHDL mcode
/// into `work` and, when it analyses, co-simulates the streams `next` gives, in order: each
/// run as given (frames, idle cycles, outputs), on the mcode simulator of `work`, without
/// progress lines, its output in `work`/sim.log (the last stream's stays). InputError from
/// the edit; SimulatorError when GHDL cannot be started.
MutatedRun run_mutated(const FileEdit* e, const std::filesystem::path& work, const NextStream& next);
/// The same with one stream.
MutatedRun run_mutated(const FileEdit* e, const std::filesystem::path& work, const cosim::GhdlRun& stream);

}  // namespace hc::mutation
