// smoke.hpp: the hand-written smoke list of the mutation campaign. Each single-point mutation
// of a list (mutation/mutations.json) is applied to a scratch copy of rtl/, analysed with
// GHDL's mcode back end and co-simulated against the unmutated cycle model (run_mutated). A
// mutant passes the campaign when the co-simulation fails and names the mutated stage as the
// first mismatching one; a mutant marked equivalent passes when the co-simulation finds nothing.
//
// List file (JSON): {"stream": {"pattern": "blocks", "size": "40x30", "frames": 2},
//   "mutants": [{"id", "kind", "file", "stage", "find", "replace", "equivalent"?}, ...]}
// where `find` must occur exactly once in rtl/<file>.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/frames/frames.hpp"

namespace hc::mutation {

/// One mutation of the list.
struct SmokeMutant {
    std::string id, kind, file, stage, find, replace;
    bool equivalent = false;
};

struct SmokeList {
    frames::FrameSource stream;     ///< what every run streams
    std::vector<SmokeMutant> mutants;
};
/// Reads a list file; throws InputError naming the file and the bad entry.
SmokeList load_smoke_list(const std::filesystem::path& p);
/// The stream as the equivalent `harris-cosim rtl` flags ("--pattern blocks --size 40x30 --frames 2").
std::string stream_flags(const frames::FrameSource& s);

/// What one co-simulation of a (mutated) RTL found.
struct SmokeOutcome {
    std::string status;             ///< "pass", "mismatch", "does not analyse", "simulator failed: ..."
    std::string stage, signal;      ///< first mismatching stage and element
    long write = 0;
    double seconds = 0;
};
/// Its JSON (a shard's result): one key a field, by the field's name.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SmokeOutcome, status, stage, signal, write, seconds)
/// The judgement of one mutant.
struct SmokeVerdict {
    SmokeMutant mutant;
    SmokeOutcome outcome;
    bool caught = false;            ///< the co-simulation failed
    bool ok = false;                ///< caught and localised (or, equivalent, not caught)
};

struct SmokeResult {
    SmokeOutcome baseline;               ///< the unmutated RTL (must pass)
    std::vector<SmokeVerdict> verdicts;
    int caught = 0, total = 0;      ///< over the non-equivalent mutants run
    int problems = 0;               ///< verdicts not ok, plus a failing baseline
};

/// Applies mutation `m` (nullptr: none, the baseline) to a copy of rtl/ in the scratch folder
/// `work` (emptied first), analyses it and co-simulates `frames`. InputError when the
/// mutation's `find` does not occur exactly once in its file.
SmokeOutcome run_smoke_mutant(const SmokeMutant* m, const frames::LoadedFrames& frames, const std::filesystem::path& work);
/// The judgement of mutant `m` from its outcome.
SmokeVerdict judge_smoke(const SmokeMutant& m, const SmokeOutcome& o);
/// The campaign's counts from the baseline's outcome and the verdicts (in list order).
SmokeResult tally_smoke(const SmokeOutcome& baseline, std::vector<SmokeVerdict> verdicts);

/// Runs the baseline and the mutants (only the one with id `only` when not empty), each in
/// its own directory under a scratch directory. `progress` gets a line per step.
SmokeResult run_smoke_list(const SmokeList& c, const std::string& only,
                            const std::function<void(const std::string&)>& progress);

/// The Markdown report (docs/mutation-smoke.md); `list` names the list file in it, `command`
/// is quoted as the command that made it (the command line as typed).
std::string smoke_markdown(const SmokeList& c, const SmokeResult& r, const std::string& list, const std::string& command);

}  // namespace hc::mutation
