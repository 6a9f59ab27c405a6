// fuzz_targets.hpp: one fuzz target per kind of file the command line reads.
//
// Purpose: each target hands arbitrary bytes to the same library reader the command line
// calls for that file (the bytes are written to a file first, because the readers take
// paths, as the command line does). The contract a target checks:
//   - the reader returns, or throws hc::InputError (or a type derived from it: the command
//     line's exit status 2) whose message names the file;
//   - anything else (another exception type, a crash, a hang) is a defect.
// A target reports a contract violation by throwing FuzzDefect; a crash or hang is caught
// by the driver (fuzz_main.cpp) or by libFuzzer (libfuzzer_entry.cpp).
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace hc::fuzz {

/// A broken contract: the reader threw something other than an input error naming the
/// file. The message says what and which reader.
struct FuzzDefect : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Target {
    std::string name;                  ///< e.g. "formats-json"
    std::string reads;                 ///< what the command line reads with it, in words
    std::string file_name;             ///< the input's file name (its suffix picks the decoder)
    std::vector<std::string> seeds;    ///< valid (and a few invalid) inputs to mutate from
    std::vector<std::string> tokens;   ///< dictionary: pieces of the format's syntax
    /// Reads `file` with the library reader (the driver has written the input there).
    std::function<void(const std::filesystem::path& file)> read;
};

/// Every target; seeds from the repository's own files (`source_dir`) and from the
/// libraries' writers (an encoded PNG and JPEG, a calib.txt, poses, ...).
std::vector<Target> targets(const std::filesystem::path& source_dir);

/// Writes `bytes` to `file` and runs the target's reader on it under the contract above.
/// Returns true when the input was accepted, false when rejected as bad input; throws
/// FuzzDefect otherwise.
bool run_one(const Target& t, const std::string& bytes, const std::filesystem::path& file);

}  // namespace hc::fuzz
