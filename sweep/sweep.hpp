// sweep.hpp: the bit-width sweep: per configuration the overflow audit, the accuracy
// against OpenCV (spec model, thesis protocol), the synthesis cost; the Pareto front of
// cost against accuracy; every Pareto point checked on the RTL (GHDL co-simulation of the
// regression set, verilate's three-way gate, Verilator on KITTI frames); per configuration also
// the correct stereo matches of the landmark chain on a few Middlebury pairs (what a bit width
// costs downstream). Reports: sweep_report.hpp.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/eval.hpp"
#include "mapping/landmarks/landmarks.hpp"
#include "sweep/cost.hpp"
#include "sweep/overflow.hpp"
#include "sweep/ranges.hpp"
#include "sweep/stage_equivalence.hpp"
#include "sweep/sweep_config.hpp"
#include "model/util/util.hpp"

namespace hc::sweep {

/// One RTL check of a configuration (several runs of one simulator).
struct TrustResult {
    bool ran = false;
    int runs = 0;              ///< simulator runs
    int failed = 0;            ///< runs that did not pass (mismatch or error)
    long mismatches = 0;       ///< mismatching cycles (GHDL) or writes (Verilator), summed
    long reads = 0;            ///< corner reads compared
    double seconds = 0;
    bool cached = false;
    std::string detail;        ///< e.g. "10/10 streams pass" or the first failure
};

/// A check as JSON (every field) and back; the trust cache's entries are these (an entry
/// written without "ran" or "cached" reads as ran, not cached).
nlohmann::json trust_to_json(const TrustResult& t);
TrustResult trust_from_json(const nlohmann::json& j);

/// A configuration's trajectory column (TrajectorySpec): APE of EKF-SLAM and of visual
/// odometry alone against the sequence's poses, the path's length, failed odometry steps.
struct Trajectory {
    double ape_slam = 0, ape_odometry = 0, path_length = 0;
    int frames = 0, odometry_failures = 0;
    double ape_percent() const { return path_length > 0 ? 100 * ape_slam / path_length : 0; }
};
/// Its JSON (sweep.json and the sweep job's shard results): {"ape_slam_m", "ape_odometry_m",
/// "path_length_m", "frames", "odometry_failures"}.
void to_json(nlohmann::json& j, const Trajectory& t);
void from_json(const nlohmann::json& j, Trajectory& t);

struct PointResult {
    Config config;
    OverflowCounts overflow;
    eval::Confusion accuracy;          ///< summed over the scored frames
    Cost cost;                         ///< variant signed (what the Pareto front uses)
    Cost cost_ghdl;                    ///< variant ghdl (thesis configuration only)
    bool has_cost_ghdl = false;
    long register_bits = 0;            ///< datapath_register_bits
    bool wraps = false;                ///< overflow.total_wrapped() > 0
    RangeReport ranges;                ///< derived ranges for every input (ranges.hpp)
    bool has_ranges = false;
    /// the stage proofs (stage_equivalence.hpp), cached under the synthesis key; only when
    /// SweepOptions::stage_proofs (has_stages false: not run)
    StageEquivalence stages;
    bool has_stages = false;
    bool pareto = false;
    bool verify = false;               ///< RTL-checked: Pareto point, thesis, or a finding (sweep_report.hpp)
    double eval_seconds = 0, overflow_seconds = 0;
    TrustResult rtl, verilator;
    bool has_landmarks = false;        ///< the landmark column was scored (SweepResult::landmark_pairs)
    landmarks::Totals landmarks;       ///< correct stereo matches downstream (score_formats)
    bool has_trajectory = false;       ///< the trajectory column was scored (SweepResult::trajectory_run)
    Trajectory trajectory;
    /// verilate's three-way gate (GHDL / Verilator / model on small frames) for these formats:
    /// runs 1, failed 1 on a translation or RTL fault; seconds: the gate's own run (also
    /// when the verdict comes from the cache); detail: the verdict
    TrustResult gate;
};

struct SweepOptions {
    std::filesystem::path spec_file;
    std::filesystem::path out;
    std::filesystem::path cache;       ///< synthesis + range + trust cache
    std::filesystem::path kitti;       ///< KITTI root (holds sequences/NN)
    std::filesystem::path regression_set;   ///< golden/regression-set.txt: the GHDL checks' streams
    std::filesystem::path middlebury;  ///< Middlebury 2006 half-size folder of the landmark column ("" = no column)
    std::string ghdl_backend = "gcc";  ///< GHDL back end of the RTL checks (cosim::run_ghdl)
    int threads = 0;                   ///< accuracy / overflow threads (0: all cores)
    int jobs = 2;                      ///< synthesis and GHDL processes at once (Verilator runs one at a time)
    bool trust = true;                 ///< run the RTL checks of the Pareto points
    /// prove every configuration's datapath stages equal to the model (stage_equivalence.hpp;
    /// about 25 to 50 s of z3 and cvc5 per configuration, once: cached under the synthesis key)
    bool stage_proofs = false;
    bool progress = true;
};

struct SweepResult {
    SweepSpec spec;
    std::vector<PointResult> points;
    std::string stream;                ///< what the accuracy was measured on
    int scored_frames = 0;
    std::string landmark_pairs;        ///< what the landmark column was scored on, or why it is absent
    std::string trajectory_run;        ///< what the trajectory column was scored on, or why it is absent
    double seconds_trajectory = 0;
    double seconds_load = 0, seconds_reference = 0, seconds_cost = 0, seconds_accuracy = 0,
           seconds_landmarks = 0, seconds_trust = 0, seconds_total = 0;
    int synthesised = 0, synth_cached = 0;
    int gates_run = 0, gates_cached = 0;
    double gate_seconds_sum = 0;       ///< wall time of the gates run now (cached ones: 0)
    double synth_seconds_sum = 0;      ///< sum of synthesis times of the runs made now
    std::string command;
    std::string regression_set = "golden/regression-set.txt";   ///< the GHDL checks' streams, as the reports name them
};

/// Pareto front: minimise LUTs and DSPs, maximise F1; only configurations that do not wrap.
void mark_pareto(std::vector<PointResult>& pts);
/// The points whose RTL is checked: the Pareto front, the thesis configuration and the
/// findings' points (findings() in sweep_report.hpp), which need not be Pareto-optimal.
void mark_verify(SweepResult& r);

/// The landmark column's stereo pairs: the scenes of `spec` under `middlebury` (a Middlebury
/// 2006 half-size folder), with their ground truth. InputError naming a missing scene.
landmarks::Dataset landmark_dataset(const std::filesystem::path& middlebury, const LandmarkSpec& spec);
/// What landmark_dataset loaded, for the reports ("Middlebury 2006 half: Aloe, Rocks1; ...").
std::string describe_landmark_pairs(const landmarks::Dataset& ds, const LandmarkSpec& spec);
/// The landmark column of every point: landmarks::score_formats(ds, formats, spec model,
/// {g, h}, thesis matching), configurations in parallel on `threads` (0: all cores).
/// The trajectory column of every point, one after the other (slam::run_kitti_sequence on
/// the sequence under `kitti`); returns what it was scored on. InputError (slam's or
/// landmarks') for a sequence without stereo pairs or poses, or a descriptor that is not binary.
std::string score_trajectories(std::vector<PointResult>& pts, const std::filesystem::path& kitti, const TrajectorySpec& spec,
                               bool progress);
void score_landmarks(std::vector<PointResult>& pts, const landmarks::Dataset& ds, const LandmarkSpec& spec,
                     int threads);

/// The whole sweep (throws InputError on bad input, SimulatorError on a tool failure):
/// evaluate_points() on every configuration, mark_pareto(), mark_verify(), check_points().
/// Progress on stderr.
SweepResult run_sweep(const SweepOptions& o);

/// What the per-configuration phases measure for some configurations of a spec.
struct PointsRun {
    std::vector<PointResult> points;   ///< in the order asked for; pareto/verify not set
    std::string stream;
    int scored_frames = 0;
    double seconds_load = 0, seconds_reference = 0, seconds_cost = 0, seconds_accuracy = 0;
    int synthesised = 0, synth_cached = 0;
    double synth_seconds_sum = 0;
    std::string landmark_pairs;          ///< as SweepResult::landmark_pairs
    double seconds_landmarks = 0;
    std::string trajectory_run;          ///< as SweepResult::trajectory_run
    double seconds_trajectory = 0;
};
/// Synthesis cost, derived ranges and (o.stage_proofs) the stage proofs (both cached under the synthesis key), overflow audit, accuracy and the landmark column of the configurations `which` (indices into
/// spec.configs; InputError for one out of range). Each point depends on its configuration
/// only, so any split of the indices gives the same points.
PointsRun evaluate_points(const SweepSpec& spec, const std::vector<size_t>& which, const SweepOptions& o);
/// The RTL checks (cosim::run_ghdl, vl::run_verilate) of the points marked verify, when
/// o.trust and the spec asks for them, `o.jobs` at a time in this process (plan_checks,
/// run_check, apply_check); sets r.seconds_trust.
void check_points(SweepResult& r, const SweepOptions& o);

// ---- the RTL checks one by one (what check_points runs, and what a sharded sweep runs as
// shards of its own job kind) -----------------------------------------------------------

/// Which simulator an RTL check runs.
enum class CheckKind {
    gate,        ///< verilate's three-way gate (GHDL / Verilator / model on small frames)
    verilator,   ///< Verilator on the trust spec's KITTI pairs
    ghdl,        ///< GHDL co-simulation of one stream of the regression set
};
const char* check_kind_name(CheckKind k);
/// Inverse of check_kind_name; InputError for another name.
CheckKind check_kind_from_name(const std::string& name);

/// One RTL check of a point marked verify.
struct CheckTask {
    size_t point = 0;          ///< index into SweepResult::points
    CheckKind kind = CheckKind::ghdl;
    int stream = -1;           ///< ghdl: index into CheckPlan::streams
};

/// The RTL checks of a result, in the order they run (the gates, then the Verilator runs,
/// the longest, then the GHDL streams), and what they share.
struct CheckPlan {
    std::vector<CheckTask> tasks;                 ///< empty: nothing to check
    std::vector<std::string> keys;                ///< per point: the trust cache's key ("" when not verified)
    std::vector<util::RegressionStream> streams;  ///< the GHDL checks' streams (o.regression_set)
};
/// The checks of the points marked verify (none unless o.trust and the spec asks for some);
/// writes each such point's formats to o.out/configs/NAME.json.
CheckPlan plan_checks(const SweepResult& r, const SweepOptions& o);

/// What one check found.
struct CheckOutcome {
    TrustResult one;                  ///< runs 1; failed 1 unless it passed
    std::string status;               ///< "pass", or what went wrong
    std::filesystem::path log;        ///< the simulator's log, relative to o.out
    bool gate_cached = false;         ///< gate: the verdict was recorded earlier
};
/// Runs checks of one spec: each in a child simulator process (Verilator's in this process,
/// one at a time), or read from the trust cache under o.cache when it passed before; a run
/// that passes is recorded there at once, so an interrupted sweep keeps what it finished.
/// The Verilator runs' KITTI pairs are loaded on the first that needs them. Logs go to
/// o.out/trust/NAME/.
class CheckRunner {
public:
    CheckRunner(const SweepSpec& spec, const SweepOptions& o);
    ~CheckRunner();
    /// Checks `formats` (the point's configuration `name`, trust cache key `key`).
    CheckOutcome run(const CheckTask& t, const Config& config, const std::string& key,
                     const std::vector<util::RegressionStream>& streams);

private:
    struct State;
    std::unique_ptr<State> s_;
};
/// Adds an outcome to its point's check (and the gate counts of r); a failure's detail names
/// its log under o.out. Outcomes applied in the plan's order give the same result whatever
/// ran them.
void apply_check(SweepResult& r, const CheckPlan& plan, const CheckTask& t, const CheckOutcome& c,
                 const SweepOptions& o);
/// After the last apply_check: the summary detail of every check that passed.
void finish_checks(SweepResult& r);

}  // namespace hc::sweep
