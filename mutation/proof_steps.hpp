// proof_steps.hpp: the steps the proofs of campaign.cpp and assume_guarantee.cpp share (not
// part of the library's interface).
#pragma once

#include <filesystem>
#include <string>

#include "mutation/campaign.hpp"

namespace hc::mutation {

/// GHDL synthesises `entity` of the RTL in `rtl` (empty: the source tree's rtl/) to
/// `work`/`side`.v; the command, with the paths shown as rtl/ and mutant-rtl/, is appended to
/// p.synth. False (and p.output says why) when GHDL fails.
bool synthesise(const std::string& entity, const fs::path& rtl, const fs::path& work, const std::string& side, Proof& p);
/// gold.v (rtl/) and gate.v (rtl/ with `m` applied) of m's proof entity, in `work`.
bool synthesise_pair(const Mutant& m, const fs::path& work, Proof& p);
/// The yosys commands that read gold.v and gate.v as modules `gold` and `gate` (see prove).
std::string load_pair_script(const Mutant& m);
/// Runs `script` as `work`/`method`.ys under a limit of `timeout_s` seconds; p.method,
/// p.script and p.output (the log's tail, and the limit when it stopped yosys) are set. True
/// when yosys succeeded.
bool run_yosys(const std::string& method, const std::string& script, const fs::path& work, int timeout_s, Proof& p);

}  // namespace hc::mutation
