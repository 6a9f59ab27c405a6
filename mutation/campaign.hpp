// campaign.hpp: the generated mutation campaign. Every mutant the generator (vhdl_mutants.hpp)
// makes from rtl/ is applied to a scratch copy of rtl/ (run_mutated) and judged (Fate):
//   stillborn   the mutated RTL does not analyse (GHDL mcode) or does not elaborate (GHDL
//               reports an error during elaboration, e.g. a static index out of bounds)
//   killed      a co-simulation against the unmutated cycle model fails: a mismatch, a
//               metavalue, or a simulator that stops early (the regression would fail)
//   equivalent  every stimulus passes and a solver proves mutant and original equal:
//               GHDL synthesises the entity holding the mutation (the package's mutants:
//               harris_top) at small geometry generics to Verilog, both sides, and yosys
//               proves them equal (equiv_make/equiv_simple/equiv_induct, else a miter and
//               sat -tempinduct from all registers zero, every input free)
//   equivalent-assuming
//               every stimulus passes, the proofs above fail, and yosys proves mutant and
//               original equal under assumptions on the entity's inputs that are themselves
//               proven on the netlists of the stages driving them (prove_assuming)
//   surviving   every stimulus passes and no proof succeeds (the proof's output is kept)
// The stimuli run in order and stop at the first kill: a quick stream first, then the
// longer ones (streams of the synthetic regression set, more chained frames, idle cycles,
// a KITTI crop when the data is present).
//
// Errors: InputError (an unknown mutant name, class or file in a selection, a bad stimulus),
// SimulatorError (GHDL or yosys cannot be started).
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/frames/frames.hpp"
#include "model/harris/harris_pkg.hpp"
#include "mutation/vhdl_mutants.hpp"

namespace hc::mutation {

namespace fs = std::filesystem;
using nlohmann::json;

/// A selection of the generated set (all empty: every mutant).
struct Selection {
    std::vector<std::string> only;      ///< mutant names, or name prefixes ("sobel_x.vhd:30:")
    std::vector<std::string> classes;   ///< class names (class_name)
    std::vector<std::string> files;     ///< rtl file names ("sobel_x.vhd")
};

/// Every mutant of the RTL files in `rtl_dir` (empty: the source tree's rtl/), in analysis
/// order of the files, each file's mutants in the generator's order.
std::vector<Mutant> generate_all(const fs::path& rtl_dir = {});
/// The mutants of `all` that `s` selects, in order. InputError for a name, class or file
/// that selects nothing.
std::vector<Mutant> select(const std::vector<Mutant>& all, const Selection& s);

/// The entity a proof synthesises for a mutant of `file` (its entity; the package's: harris_top).
std::string proof_entity(const std::string& file);

/// One stimulus: frames and the idle-cycle rate.
struct Stimulus {
    std::string name;                   ///< "quick", "random_40x30", "kitti01_64x48", ...
    frames::FrameSource source;
    int idle_every = 0;
};
json to_json(const Stimulus& s);
Stimulus stimulus_from_json(const json& j);

/// The quick stream: two chained 24x16 `blocks` frames.
Stimulus quick_stimulus();
/// The longer streams: four chained random 24x16 frames (seed 7) with an idle cycle every 3
/// writes; the regression set's (golden/regression-set.txt) random 40x30, twins 40x30 and
/// extremes 33x21 streams, in its order; three `blocks` 33x21 frames of seed 18, where a response equals
/// its threshold; and, when `data_dir` is not empty, KITTI 01's first stereo pair cropped to
/// 32x24.
std::vector<Stimulus> long_stimuli(const fs::path& data_dir);

/// The proof attempt of a survivor.
struct Proof {
    bool equivalent = false;
    std::string method;      ///< "equiv" (equiv_simple + equiv_induct), "equiv-named" (the same, GHDL's net names
                             ///< hidden), "miter" (sat -tempinduct), or ""
    std::string entity;
    std::string script;      ///< the yosys script that gave the verdict (the last one tried)
    std::string synth;       ///< the GHDL commands that made gold.v and gate.v
    std::string output;      ///< the tail of the last attempt's yosys (or GHDL) output
    std::vector<std::string> assumptions;   ///< method "assume-guarantee": the proven guarantees it assumes
    double seconds = 0;
    /// the verilog_reading() an equivalence was proven under; "" where none was, or where it was
    /// read from a verdict list written before its CSV had the column
    std::string reading;
};
/// Its JSON (inside a Result's): one key a field, by the field's name.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Proof, equivalent, method, entity, script, synth, output, assumptions, seconds, reading)

/// A mutant's verdict (the header comment says what each means).
enum class Fate { stillborn, killed, equivalent, equivalent_assuming, surviving };
/// Each verdict's name in the JSON, the CSV and the reports: the one table both ways use.
inline constexpr std::array<std::pair<Fate, std::string_view>, 5> fate_names = {{
    {Fate::stillborn, "stillborn"},
    {Fate::killed, "killed"},
    {Fate::equivalent, "equivalent"},
    {Fate::equivalent_assuming, "equivalent-assuming"},
    {Fate::surviving, "surviving"},
}};
/// The name of `f` (fate_names).
std::string fate_name(Fate f);
/// The verdict named `name` (fate_names); nullopt for any other text.
std::optional<Fate> fate_from_name(std::string_view name);

/// A mutant's verdict and what gave it.
struct Result {
    std::string name, file, entity, cls;
    int line = 0, column = 0;
    Fate fate = Fate::surviving;
    std::string detail;      ///< stillborn: why; killed: "mismatch", "metavalue" or "simulator failed"
    std::string killed_by;   ///< the stimulus that killed it
    std::string stage, signal;
    long write = 0;
    int runs = 0;            ///< co-simulations run
    double analyse_seconds = 0, sim_seconds = 0, seconds = 0;
    Proof proof;
};
json to_json(const Result& r);
Result result_from_json(const json& j);

struct Options {
    Stimulus quick = quick_stimulus();
    std::vector<Stimulus> longer;        ///< run on the quick stream's survivors
    bool prove = true;                   ///< prove the survivors of every stimulus
    int proof_timeout_s = 120;           ///< per yosys run
    std::function<void(const std::string&)> progress;   ///< a line per step (may be empty)
};

/// Judges one mutant in a scratch directory of its own.
Result run_mutant(const Mutant& m, const Options& o);
/// The control of a campaign: the unmutated rtl/ through the same mutated-copy run, on the
/// quick stimulus. A verdict means something only when this passes, so SimulatorError (status
/// 3) when the copy does not analyse or elaborate, or the co-simulation fails or disagrees
/// (a missing testbench, a stale build, a broken tool): the message names the failure.
void check_unmutated(const Options& o);
/// The proof of a mutant alone (`work`: a directory for the netlists and scripts).
Proof prove(const Mutant& m, const fs::path& work, int timeout_s);

/// A closed interval of integers.
struct Interval {
    long long lo = 0, hi = 0;
};
/// What the stages upstream of harris_response produce for every 8-bit pixel window, by
/// interval arithmetic on the stage functions at formats `f` (a Sobel gradient is at most
/// four pixels' worth; ix*ix and ix*iy cut by 2^m_drop; nine of those summed and cut by
/// 2^bf_drop; each cut a floor). Each is then proven on the stage's netlist (guarantees).
struct StageRanges {
    Interval sobel;          ///< ix, iy
    Interval m_square;       ///< M's a, c
    Interval m_cross;        ///< M's b
    Interval bf_square;      ///< block sums of a and c: harris_response's a, c
    Interval bf_cross;       ///< block sums of b: harris_response's b
};
/// InputError when a range does not fit the register holding it (then no range is proven).
StageRanges derive_ranges(const Formats& f = {});

/// A property of one entity's outputs, proven on its GHDL netlist (default generics) by yosys:
/// a Verilog module `chk` instantiates the entity, assumes the properties of its inputs that
/// the guarantees named in `assumes` prove for the stages driving them, and asserts the
/// property; `sat -tempinduct -prove-asserts -set-assumes` from all registers zero.
struct Guarantee {
    std::string name;                   ///< "m_products: a, c in [0, 32512], b in [-32513, 32512]"
    std::string entity;
    std::vector<std::string> assumes;
    std::string checker;                ///< the Verilog of `chk`
};
/// The guarantees harris_response's proofs assume, upstream first: sobel_x, sobel_y (no
/// assumption: every 8-bit window), m_products (under the Sobel range), block_filter on the
/// M ranges of a and c and on that of b. The ranges are `r`'s, proven or refused as given.
std::vector<Guarantee> response_guarantees(const StageRanges& r);
/// The guarantee threshold's proofs assume: control_shift_register's t is all zero until a
/// write after the last reset (so threshold's enable, t(5) in harris_top, is 0 at the first
/// write after reset).
Guarantee enable_guarantee();
/// The yosys script proving `g`, run beside `<entity>.v` (the checker inline).
std::string guarantee_script(const Guarantee& g);
/// Every guarantee of response_guarantees(r) and enable_guarantee() as a runnable script: file
/// name (guarantee_<k>_<entity>.ys) and text (its name, what it assumes and the GHDL command
/// that makes `<entity>.v` as comments).
std::vector<std::pair<std::string, std::string>> guarantee_files(const StageRanges& r = derive_ranges());
/// Proves `g` in `work` (its own folder); p.equivalent means proven.
Proof prove_guarantee(const Guarantee& g, const fs::path& work, int timeout_s);

/// Whether prove_assuming has assumptions for the entity of `file` (harris_response, threshold).
bool has_assumptions(const std::string& file);
/// The proof of `m` under assumptions on its entity's inputs: first every guarantee they come
/// from is proven (any that fails refuses the proof, p.output naming it), then a miter of gold
/// and gate with the assumptions as $assume cells, `opt` sharing the cells both sides have in
/// common, and `sat -tempinduct` proving the outputs equal together with invariants that make
/// the induction close (harris_response: the step-1 products' top bits zero, the k-terms
/// equal; threshold: r0_delay equal once a write followed the reset). Method "assume-guarantee".
Proof prove_assuming(const Mutant& m, const fs::path& work, int timeout_s,
                     const StageRanges& r = derive_ranges());

/// One input of a failed proof's counterexample: its value at a time step (1: the first).
struct CexValue {
    int step = 0;
    std::string signal;     ///< yosys's name without the leading backslash ("in_a")
    long long value = 0;    ///< the bits read as a signed number
};
/// The inputs of the base-case counterexample of a failed prove_assuming proof made in `work`,
/// read from the `sat` log that proof printed them to (its `-show-inputs`, so no second solver
/// run). Empty when yosys found no base-case counterexample (the proof holds for `-maxsteps`
/// steps, or only its induction step fails); std::logic_error for a proof of another method.
std::vector<CexValue> counterexample(const Proof& p, const fs::path& work);

/// Verdicts of the mutants `sel` from `old` (results_from_csv of an earlier run on this rtl/):
/// killed, stillborn and unconditionally proven ones stand; a surviving one, or one proven
/// under assumptions, is proven again by prove_assuming (`jobs` at a time, `timeout_s` per
/// yosys run) and is "equivalent-assuming" or "surviving" by that proof alone. An
/// unconditionally proven one made under another reading of GHDL's Verilog than
/// verilog_reading() (or under an unrecorded one) is proven again by prove, then, where that
/// fails, by prove_assuming. InputError when `old` has no verdict for a mutant of `sel`.
struct Reuse {
    std::vector<Result> results;   ///< in the order of `sel`
    int reused = 0;                ///< verdicts taken as they were
    int reread = 0;                ///< unconditional proofs made again under this reading
    double wall_seconds = 0;       ///< of the proofs run again
};
/// Whether reuse_verdicts takes a verdict as it was read: killed, stillborn, or proven
/// unconditionally under this verilog_reading().
bool stands_as_read(const Result& r);
Reuse reuse_verdicts(const std::vector<Result>& old, const std::vector<Mutant>& sel, int jobs, int timeout_s,
                     const std::function<void(const std::string&)>& progress);

/// Counts of a group of results.
struct Tally {
    int mutants = 0, stillborn = 0, killed = 0, equivalent = 0, surviving = 0;
    int assuming = 0;        ///< proven equivalent under proven assumptions (not in `equivalent`)
    double seconds = 0;
    /// killed / (mutants - stillborn - equivalent - assuming); 1 when nothing is left to kill.
    double score() const;
};
Tally tally(const std::vector<Result>& rs);

/// What the report says about how it was made.
struct ReportInfo {
    std::string command;            ///< the command that made it
    Stimulus quick;
    std::vector<Stimulus> longer;
    int generated = 0;              ///< mutants the generator makes of rtl/ (the run may be a subset)
    std::string runner;             ///< "local, 2 jobs, 74 shards"
    double wall_seconds = 0;
    std::string proofs_dir;         ///< where the proven mutants' scripts are written (relative)
    std::string reused;             ///< how verdicts of an earlier run were reused (empty: none were)
};
/// The Markdown report: per class and per entity, the score, time per mutant, the survivors
/// with their proof output, the proven ones with their script's file.
std::string markdown(const std::vector<Result>& rs, const ReportInfo& info);
/// A hash over the names and texts of the RTL files (cosim::rtl_sources()): the RTL a verdict is about.
std::string rtl_hash();
/// A hash of how the proofs read GHDL's Verilog (cosim::kVerilogReading): a proof made under
/// another reading is made again before it is reused.
std::string verilog_reading();
/// One line per mutant: name,file,line,column,class,entity,fate,detail,killed_by,stage,signal,write,runs,
/// seconds,proof_method,assumptions (';'-separated),rtl_hash (`rtl`: the RTL the verdicts are about),
/// verilog_reading (Proof::reading).
std::string csv(const std::vector<Result>& rs, const std::string& rtl);
/// The verdicts of a CSV that csv() wrote (`source` names it in errors): every field csv()
/// keeps; a proof's script and output are not in it. A list written before the column
/// verilog_reading (17 fields a line) is read with every reading empty. InputError for a
/// malformed line or a line whose rtl_hash is not `rtl` (verdicts about other RTL are not reused).
std::vector<Result> results_from_csv(const std::string& text, const std::string& source, const std::string& rtl);
/// The file name of a proven mutant's script in ReportInfo::proofs_dir.
std::string proof_file_name(const Result& r);

/// Writes a campaign's files: the Markdown report at `md`, its verdict CSV beside it (`md`
/// with the extension .csv, csv() over rtl_hash()), and in the folder mutation-proofs/
/// beside it the script of every mutant proven here (a reused verdict keeps the file of the
/// run that proved it) and, when a proof assumed them, the guarantees' scripts. The report
/// names that folder relative to its parent (`info.proofs_dir` is set so).
void write_report_files(const std::filesystem::path& md, const std::vector<Result>& rs, ReportInfo info);
/// The report's paragraph on the verdicts reuse_verdicts reused from `csv_file` and those it
/// proved again, `jobs` at a time.
std::string reuse_note(const Reuse& u, const std::string& csv_file, int jobs);

}  // namespace hc::mutation
