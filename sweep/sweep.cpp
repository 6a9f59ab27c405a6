// sweep.cpp: see sweep.hpp. Phases, each parallel over the cores:
//   1. frames + OpenCV reference masks (once for all configurations)
//   2. cost: synthesis of every configuration, `jobs` at a time (cache hits instant);
//      derived ranges of every configuration (ranges.hpp), cached by the synthesis key;
//      with o.stage_proofs the stage proofs (stage_equivalence.hpp), cached by the same key
//   3. accuracy and overflow audit per configuration (frames in parallel, TBB); correct stereo
//      matches of the landmark chain per configuration (configurations in parallel, TBB)
//   4. Pareto front; RTL checks of its points, `jobs` simulator processes at a time
//      (results cached like the synthesis: an unchanged point is not simulated again):
//      GHDL on the regression set, verilate's three-way gate, Verilator on KITTI pairs
#include "sweep/sweep.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "cosim/cosim.hpp"
#include "cosim/verilator/verilate.hpp"
#include "io/frames/frames.hpp"
#include "golden/golden.hpp"
#include "model/harris/formats_json.hpp"
#include "mapping/slam/landmark_frames.hpp"
#include "model/util/util.hpp"
#include "sweep/pareto.hpp"
#include "sweep/sweep_report.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace hc::sweep {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::mutex g_print;
void progress(bool on, const std::string& s) {
    if (!on) return;
    std::lock_guard<std::mutex> l(g_print);
    std::fprintf(stderr, "sweep: %s\n", s.c_str());
}

/// Runs `n` tasks on `jobs` threads (each task typically waits for a child process).
void run_pool(size_t n, int jobs, const std::function<void(size_t)>& task) {
    std::atomic<size_t> next{0};
    std::vector<std::thread> ts;
    std::mutex err_m;
    std::exception_ptr err;
    for (int j = 0; j < std::max(1, jobs); ++j)
        ts.emplace_back([&] {
            for (size_t i; (i = next++) < n;) {
                try {
                    task(i);
                } catch (...) {
                    std::lock_guard<std::mutex> l(err_m);
                    if (!err) err = std::current_exception();
                    next = n;   // stop handing out work
                }
            }
        });
    for (auto& t : ts) t.join();
    if (err) std::rethrow_exception(err);
}

/// Adds one run (or a cached run) to a point's check; cached only if every run was.
void add_run(TrustResult& t, const TrustResult& one) {
    const bool first = !t.ran;
    t.ran = true;
    t.runs += one.runs;
    t.failed += one.failed;
    t.mismatches += one.mismatches;
    t.reads += one.reads;
    t.seconds += one.seconds;
    t.cached = (first || t.cached) && one.cached;
    if (t.detail.empty()) t.detail = one.detail;
}

}  // namespace

json trust_to_json(const TrustResult& t) {
    return {{"ran", t.ran},         {"runs", t.runs},   {"failed", t.failed},   {"mismatches", t.mismatches},
            {"reads", t.reads},     {"seconds", t.seconds}, {"cached", t.cached}, {"detail", t.detail}};
}

TrustResult trust_from_json(const json& j) {
    TrustResult t;
    t.ran = j.value("ran", true);
    t.cached = j.value("cached", false);
    t.runs = j.at("runs");
    t.failed = j.at("failed");
    t.mismatches = j.at("mismatches");
    t.reads = j.at("reads");
    t.seconds = j.at("seconds");
    t.detail = j.at("detail");
    return t;
}

void mark_pareto(std::vector<PointResult>& pts) {
    std::vector<std::vector<double>> obj;
    std::vector<bool> ok;
    for (const auto& p : pts) {
        obj.push_back({double(p.cost.luts), double(p.cost.dsps), -p.accuracy.f1()});
        ok.push_back(!p.wraps);
    }
    const auto front = pareto_front(obj, ok);
    for (size_t i = 0; i < pts.size(); ++i) pts[i].pareto = front[i];
}

void mark_verify(SweepResult& r) {
    for (auto& p : r.points) p.verify = p.pareto;
    const Findings f = findings(r);
    for (int i : {f.thesis, f.cheapest_as_good, f.best_at_thesis_cost})
        if (i >= 0) r.points[i].verify = true;
}

landmarks::Dataset landmark_dataset(const fs::path& middlebury, const LandmarkSpec& spec) {
    landmarks::Dataset ds;
    ds.name = "middlebury-" + middlebury.filename().string();
    for (const auto& name : spec.scenes) {
        const fs::path dir = middlebury / name;
        if (!fs::is_directory(dir))
            throw InputError("landmark column: Middlebury scene '" + dir.string() + "' is not a directory");
        try {
            landmarks::MiddleburyScene sc = landmarks::load_middlebury(dir);
            ds.calib.push_back(landmarks::middlebury_calib(sc.scale, sc.dmin_full, sc.images.left.size()));
            ds.pairs.push_back(std::move(sc.images));
            ds.disparity.push_back(std::move(sc.disparity));
        } catch (const hc::InputError& e) {
            throw InputError(std::string("landmark column: ") + e.what());
        }
    }
    return ds;
}

std::string describe_landmark_pairs(const landmarks::Dataset& ds, const LandmarkSpec& spec) {
    std::string names;
    for (const auto& p : ds.pairs) names += (names.empty() ? "" : ", ") + p.name;
    return fmt::format("{} {} (view1 + view5, ground truth disp1), spec-model corners (a seed pair streamed first), "
                       "grid g = {}, h = {}, appendix F matching",
                       ds.name, names, spec.g, spec.h);
}

void score_landmarks(std::vector<PointResult>& pts, const landmarks::Dataset& ds, const LandmarkSpec& spec, int threads) {
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    const int before = cv::getNumThreads();
    cv::setNumThreads(1);
    arena.execute([&] {
        tbb::parallel_for(size_t{0}, pts.size(), [&](size_t i) {
            pts[i].landmarks = landmarks::score_formats(ds, pts[i].config.formats, landmarks::Detector::spec,
                                                        landmarks::GridParams{spec.g, spec.h}, landmarks::MatchParams{});
            pts[i].has_landmarks = true;
        });
    });
    cv::setNumThreads(before);
}

std::string score_trajectories(std::vector<PointResult>& pts, const fs::path& kitti, const TrajectorySpec& spec,
                               bool show) {
    slam::KittiRunOptions k;
    k.stereo_landmarks = true;
    k.pipeline.detector = landmarks::Detector::spec;
    k.pipeline.descriptor = landmarks::parse_descriptor(spec.descriptor);
    k.keep_frames = false;   // the scores only
    for (auto& p : pts) {
        k.pipeline.corners.formats = p.config.formats;
        const slam::KittiRun r = slam::run_kitti_sequence(kitti, spec.sequence, k);
        p.trajectory = {r.run.slam_metrics.ape, r.run.odometry_metrics.ape, r.run.slam_metrics.path_length,
                        static_cast<int>(r.run.scored_frames), r.vo.failures};
        p.has_trajectory = true;
        progress(show, fmt::format("[trajectory] {}: APE EKF-SLAM {:.3f} m ({:.2f} % of {:.1f} m), visual odometry alone "
                                   "{:.3f} m, {} odometry failures",
                                   p.config.name, p.trajectory.ape_slam, p.trajectory.ape_percent(), p.trajectory.path_length,
                                   p.trajectory.ape_odometry, p.trajectory.odometry_failures));
    }
    return fmt::format("KITTI {}: {} stereo pairs, spec-model corners, {} descriptor, visual odometry and EKF-SLAM "
                       "(slam::run_kitti_sequence defaults; poses/{}.txt only scores)",
                       spec.sequence, pts.empty() ? 0 : pts.front().trajectory.frames, spec.descriptor, spec.sequence);
}

namespace {

// ---- the phases of evaluate_points, each on every point of `res` ----------------------

// A scored frame: all but the first stereo pair's, which only seed the threshold.
bool scored(const eval::Stream& s, size_t k) { return s.pair_index[k] != s.pair_index.front(); }

// 2. cost: yosys synthesis (cached), and the thesis's configuration also as GHDL writes it.
void cost_phase(PointsRun& res, const SweepSpec& spec, const SweepOptions& o) {
    const size_t n = res.points.size();
    const auto t = Clock::now();
    CostOptions co;
    co.rtl_sources = cosim::rtl_sources();
    co.cache_dir = o.cache / "synth";
    co.geometry = spec.cost_geometry;
    const CostContext ctx(co);
    struct Job { size_t point; Variant v; };
    std::vector<Job> jobs;
    for (size_t i = 0; i < n; ++i) {
        jobs.push_back({i, Variant::signed_mul});
        if (res.points[i].config.formats == Formats{}) jobs.push_back({i, Variant::ghdl});   // the DSP note
    }
    std::atomic<int> done{0};
    std::mutex m;
    run_pool(jobs.size(), o.jobs, [&](size_t k) {
        const Job& j = jobs[k];
        const Cost c = synth_cost(ctx, res.points[j.point].config.formats, j.v);
        {
            std::lock_guard<std::mutex> l(m);
            PointResult& p = res.points[j.point];
            if (j.v == Variant::signed_mul) p.cost = c;
            else { p.cost_ghdl = c; p.has_cost_ghdl = true; }
            if (c.cached) ++res.synth_cached;
            else { ++res.synthesised; res.synth_seconds_sum += c.seconds; }
        }
        progress(o.progress, fmt::format("[cost {}/{}] {} ({}): {} LUT, {} FF, {} DSP, {} CARRY4 {}", ++done, jobs.size(),
                                         res.points[j.point].config.name, variant_name(j.v), c.luts, c.ffs, c.dsps, c.carry4,
                                         c.cached ? "(cached)" : fmt::format("({:.0f} s)", c.seconds)));
    });
    res.seconds_cost = since(t);
}

// 2b. derived ranges, cached under the synthesis key.
void ranges_phase(PointsRun& res, const SweepOptions& o) {
    const size_t n = res.points.size();
    for (size_t i = 0; i < n; ++i) {
        PointResult& p = res.points[i];
        p.ranges = cached_ranges(p.config.formats, p.cost.key, o.cache / "ranges");
        p.has_ranges = true;
        progress(o.progress, fmt::format("[ranges {}/{}] {}: {} ({})", i + 1, n, p.config.name, p.ranges.summary(),
                                         p.ranges.cached ? "cached"
                                                         : fmt::format("{:.2f} s", p.ranges.seconds_interval + p.ranges.seconds_search +
                                                                                       p.ranges.seconds_solver + p.ranges.seconds_netlist)));
    }
}

// 2c. the stage proofs (o.stage_proofs), cached under the synthesis key; a configuration proven
// now keeps its netlists, queries and rerun commands under o.out/stages/<name>/ (a shard, which
// has no o.out, in a scratch directory).
void stages_phase(PointsRun& res, const SweepSpec& spec, const SweepOptions& o) {
    if (!o.stage_proofs) return;
    const size_t n = res.points.size();
    for (size_t i = 0; i < n; ++i) {
        PointResult& p = res.points[i];
        StageOptions so;
        so.geometry = spec.cost_geometry;   // find_max's period: the synthesised design's, as in the key
        so.config = p.config.name;
        if (!o.out.empty()) so.dir = o.out / "stages" / p.config.name;
        p.stages = cached_stage_equivalence(p.config.formats, p.cost.key, o.cache / "stages", so);
        p.has_stages = true;
        progress(o.progress, fmt::format("[stages {}/{}] {}: {} ({})", i + 1, n, p.config.name, p.stages.column(),
                                         p.stages.cached ? "cached" : fmt::format("{:.1f} s", p.stages.seconds)));
    }
}

// 3. accuracy against the OpenCV reference `ref` on the scored frames, and the overflow audit.
void accuracy_phase(PointsRun& res, const eval::Stream& stream, const std::vector<std::vector<std::uint8_t>>& ref,
                    const SweepOptions& o) {
    const size_t n = res.points.size();
    std::vector<const Image*> frames;
    for (const auto& f : stream.frames) frames.push_back(&f);
    const auto t = Clock::now();
    for (size_t i = 0; i < n; ++i) {
        PointResult& p = res.points[i];
        const auto ta = Clock::now();
        p.overflow = count_overflows(frames, p.config.formats, o.threads);
        p.wraps = p.overflow.total_wrapped() > 0;
        p.overflow_seconds = since(ta);
        const auto tb = Clock::now();
        spec::Options so;
        so.formats = p.config.formats;
        const eval::SourceRun run = eval::run_spec(stream, so, o.threads);
        for (size_t k = 0; k < frames.size(); ++k)
            if (scored(stream, k)) p.accuracy.add(eval::classify(run.masks[k], ref[k]));
        p.eval_seconds = since(tb);
        progress(o.progress, fmt::format("[accuracy {}/{}] {}: recall {:.4f} precision {:.4f} F1 {:.4f}{} ({:.1f} s + audit {:.1f} s)",
                                         i + 1, n, p.config.name, p.accuracy.recall(), p.accuracy.precision(), p.accuracy.f1(),
                                         p.wraps ? " WRAPS: " + p.overflow.summary() : "", p.eval_seconds, p.overflow_seconds));
    }
    res.seconds_accuracy = since(t);
}

// 3b. downstream: correct stereo matches of the landmark chain.
void landmarks_phase(PointsRun& res, const SweepSpec& spec, const SweepOptions& o) {
    const auto t = Clock::now();
    if (!spec.landmarks.enabled) {
        res.landmark_pairs = "not scored (the spec's \"landmarks\" is false)";
    } else if (o.middlebury.empty()) {
        res.landmark_pairs = "not scored (no Middlebury 2006 half-size folder)";
    } else {
        const landmarks::Dataset ds = landmark_dataset(o.middlebury, spec.landmarks);
        res.landmark_pairs = describe_landmark_pairs(ds, spec.landmarks);
        progress(o.progress, "landmarks: " + res.landmark_pairs);
        score_landmarks(res.points, ds, spec.landmarks, o.threads);
        for (const auto& p : res.points)
            progress(o.progress, fmt::format("[landmarks] {}: {} correct stereo matches ({} within 1 px of the ground truth) of {}",
                                             p.config.name, p.landmarks.correct, p.landmarks.truth_correct, p.landmarks.all));
    }
    res.seconds_landmarks = since(t);
}

// 3c. downstream: the trajectory of visual odometry and EKF-SLAM from each point's corners.
void trajectory_phase(PointsRun& res, const SweepSpec& spec, const SweepOptions& o) {
    const auto t = Clock::now();
    if (!spec.trajectory.enabled)
        res.trajectory_run = "not scored (the spec has no \"trajectory\")";
    else if (!frames::is_kitti_sequence(o.kitti, spec.trajectory.sequence))
        res.trajectory_run = "not scored (no stereo pairs of KITTI " + spec.trajectory.sequence + " under " + o.kitti.string() + ")";
    else
        res.trajectory_run = score_trajectories(res.points, o.kitti, spec.trajectory, o.progress);
    res.seconds_trajectory = since(t);
}

}  // namespace

PointsRun evaluate_points(const SweepSpec& spec, const std::vector<size_t>& which, const SweepOptions& o) {
    PointsRun res;
    for (size_t i : which)
        if (i >= spec.configs.size())
            throw InputError(fmt::format("sweep: configuration {} does not exist ({} in the spec)", i, spec.configs.size()));
    const size_t n = which.size();
    cv::setNumThreads(1);   // frames run in parallel; OpenCV's own threads would oversubscribe

    // ---- 1. frames and reference -------------------------------------------------------
    auto t = Clock::now();
    const util::Range pairs = spec.pairs.empty() ? util::Range{0, 1 << 30} : util::parse_range(spec.pairs, "data.pairs");
    const eval::Stream stream = frames::load_kitti_stream(o.kitti, spec.sequence, pairs,
                                                          "sweep spec data.pairs '" + spec.pairs + "'", o.threads, 2);
    // the Verilator pairs are loaded after the cost phase: a range past the data is bad input now
    if (o.trust && !spec.trust.verilator_pairs.empty())
        (void)frames::stereo_stream(frames::open_kitti(o.kitti, spec.sequence),
                                    util::parse_range(spec.trust.verilator_pairs, "trust.verilator_pairs"),
                                    "sweep spec trust.verilator_pairs '" + spec.trust.verilator_pairs + "'");
    res.stream = stream.description;
    res.seconds_load = since(t);
    progress(o.progress, stream.description);
    t = Clock::now();
    const auto ref = eval::run_reference(stream, spec::ReferenceOptions{}, o.threads);
    res.seconds_reference = since(t);
    for (size_t k = 0; k < stream.frames.size(); ++k) res.scored_frames += scored(stream, k);

    res.points.resize(n);
    for (size_t i = 0; i < n; ++i) {
        res.points[i].config = spec.configs[which[i]];
        res.points[i].register_bits = datapath_register_bits(res.points[i].config.formats, spec.cost_geometry);
    }
    cost_phase(res, spec, o);
    ranges_phase(res, o);
    stages_phase(res, spec, o);
    accuracy_phase(res, stream, ref, o);
    landmarks_phase(res, spec, o);
    trajectory_phase(res, spec, o);
    cv::setNumThreads(1);

    return res;
}

SweepResult run_sweep(const SweepOptions& o) {
    const auto t0 = Clock::now();
    SweepResult res;
    res.spec = load_sweep_spec(o.spec_file);   // InputError: status 2
    const size_t n = res.spec.configs.size();
    progress(o.progress, fmt::format("{} configurations from {}", n, o.spec_file.string()));
    for (const auto& note : res.spec.notes) progress(o.progress, "note: " + note);
    std::vector<size_t> all(n);
    for (size_t i = 0; i < n; ++i) all[i] = i;
    PointsRun pr = evaluate_points(res.spec, all, o);
    res.points = std::move(pr.points);
    res.stream = pr.stream;
    res.scored_frames = pr.scored_frames;
    res.seconds_load = pr.seconds_load;
    res.seconds_reference = pr.seconds_reference;
    res.seconds_cost = pr.seconds_cost;
    res.seconds_accuracy = pr.seconds_accuracy;
    res.synthesised = pr.synthesised;
    res.synth_cached = pr.synth_cached;
    res.synth_seconds_sum = pr.synth_seconds_sum;
    res.landmark_pairs = pr.landmark_pairs;
    res.seconds_landmarks = pr.seconds_landmarks;
    res.trajectory_run = pr.trajectory_run;
    res.seconds_trajectory = pr.seconds_trajectory;
    mark_pareto(res.points);
    mark_verify(res);
    check_points(res, o);
    res.seconds_total = since(t0);
    return res;
}

const char* check_kind_name(CheckKind k) {
    switch (k) {
    case CheckKind::gate: return "gate";
    case CheckKind::verilator: return "verilator";
    case CheckKind::ghdl: return "ghdl";
    }
    return "?";
}

CheckKind check_kind_from_name(const std::string& name) {
    for (CheckKind k : {CheckKind::gate, CheckKind::verilator, CheckKind::ghdl})
        if (name == check_kind_name(k)) return k;
    throw InputError("unknown RTL check kind '" + name + "' (gate, verilator, ghdl)");
}

CheckPlan plan_checks(const SweepResult& res, const SweepOptions& o) {
    const SweepSpec& spec = res.spec;
    CheckPlan plan;
    const size_t n = res.points.size();
    plan.keys.resize(n);
    if (!o.trust || !(spec.trust.rtl || !spec.trust.verilator_pairs.empty() || spec.trust.verilator_gate)) return plan;
    CostOptions co;
    co.rtl_sources = cosim::rtl_sources();
    co.cache_dir = o.cache / "synth";
    co.geometry = spec.cost_geometry;
    const CostContext ctx(co);
    if (spec.trust.rtl) plan.streams = util::read_regression_set(o.regression_set);
    for (size_t i = 0; i < n; ++i) {
        const PointResult& p = res.points[i];
        if (!p.verify) continue;
        // the RTL checks depend on the RTL, the tool versions and the formats: same key basis
        plan.keys[i] = util::hex64(util::fnv1a(ctx.fingerprint + fields_text(p.config.formats, format_fields()) +
                                               fmt::format("|{}|{}|{}", spec.trust.verilator_pairs,
                                                           spec.trust.verilator_gate, spec.sequence)));
        util::write_file_atomic(o.out / "configs" / (p.config.name + ".json"),
                                formats_to_json(p.config.formats, p.config.name));
        if (spec.trust.verilator_gate) plan.tasks.push_back({i, CheckKind::gate, -1});
        if (!spec.trust.verilator_pairs.empty()) plan.tasks.push_back({i, CheckKind::verilator, -1});
        for (int st = 0; st < static_cast<int>(plan.streams.size()); ++st) plan.tasks.push_back({i, CheckKind::ghdl, st});
    }
    // gates, then Verilator runs first: they are the longest (netlist builds)
    std::stable_sort(plan.tasks.begin(), plan.tasks.end(),
                     [](const CheckTask& a, const CheckTask& b) { return a.kind < b.kind; });
    return plan;
}

namespace {

// The three-way gate of one configuration (its verdict recorded by vl::run_gate_cached).
void gate_check(CheckOutcome& c, const Config& config, const SweepOptions& o, const fs::path& rel, std::mutex& verilator_m) {
    TrustResult& one = c.one;
    std::string& status = c.status;
    c.log = rel / "gate.log";
    std::ofstream glog(o.out / c.log);
    std::string why;
    if (!vl::toolchain_available(&why)) {
        status = "no gate: " + why;
    } else {
        try {
            std::lock_guard<std::mutex> l(verilator_m);
            const vl::GateResult g = vl::run_gate_cached(config.formats, {}, vl::default_cache_dir(), glog, &c.gate_cached);
            one.reads = g.reads;
            one.cached = c.gate_cached;
            status = g.verdict == vl::GateVerdict::pass ? "pass" : std::string(vl::verdict_name(g.verdict)) + ": " + g.first;
            one.detail = g.verdict == vl::GateVerdict::pass
                             ? fmt::format("pass: {} writes, {} reads agree three ways ({:.0f} s{})", g.writes, g.reads,
                                           g.seconds, c.gate_cached ? ", recorded" : "")
                             : std::string();
            one.seconds = g.seconds;
        } catch (const SimulatorError& e) {
            status = e.what();
        }
    }
}

// The GHDL run of one configuration on one regression-set stream.
void ghdl_check(CheckOutcome& c, const Config& config, const util::RegressionStream& s, const SweepOptions& o,
                const fs::path& rel, const fs::path& dir) {
    TrustResult& one = c.one;
    std::string& status = c.status;
    const std::string tag = fmt::format("rtl-{}-{}", s.stem(), s.idle_every);
    c.log = rel / (tag + ".log");
    fs::remove(o.out / c.log);
    cosim::GhdlRun run;
    run.frames = golden::stream_frames(s);
    for (int f = 0; f < s.frames; ++f) run.frame_names.push_back(s.stem() + "#" + std::to_string(f));
    run.formats = config.formats;
    run.backend = o.ghdl_backend;
    run.keep_going = true;
    run.idle_every = s.idle_every;
    run.progress = false;
    run.log = o.out / c.log;
    run.summary_json = dir / (tag + ".json");
    run.vcd = dir / (tag + ".vcd");
    try {
        const cosim::GhdlResult r = cosim::run_ghdl(run);
        one.mismatches = r.summary.mismatching_cycles + r.summary.read_mismatches;
        one.reads = r.summary.reads;
        const bool ok = r.summary.pass() && r.summary.complete && r.simulator_status == 0;
        status = ok ? "pass" : r.summary.mismatching_cycles > 0 ? "mismatch" : "incomplete";
    } catch (const SimulatorError& e) {
        status = e.what();
    }
}

// The Verilator run of one configuration on the trust spec's KITTI pairs.
void verilator_check(CheckOutcome& c, const Config& config, const frames::Stream& stream, const SweepOptions& o,
                     const fs::path& rel, std::mutex& verilator_m) {
    TrustResult& one = c.one;
    std::string& status = c.status;
    c.log = rel / "verilate.log";
    fs::remove(o.out / c.log);
    vl::VerilateRun run;
    run.frames = stream.frames;
    run.frame_names = stream.names;
    run.formats = config.formats;
    run.gate = false;   // the gate is its own check
    run.keep_going = true;
    std::ofstream vlog(o.out / c.log);
    try {
        std::lock_guard<std::mutex> l(verilator_m);
        const vl::VerilateResult r = vl::run_verilate(run, vlog);
        if (r.run) {
            one.mismatches = r.run->mismatches;
            one.reads = r.run->reads;
        }
        status = r.status();
    } catch (const SimulatorError& e) {
        status = e.what();
    }
}

}  // namespace

struct CheckRunner::State {
    SweepSpec spec;
    SweepOptions o;
    fs::path trust_cache;
    std::mutex verilator_m;   // one verilated design at a time (Verilator's runtime is process-global)
    std::once_flag vl_loaded;
    frames::Stream vl_stream;   // the Verilator runs' frames: the KITTI pairs of the trust spec
};

CheckRunner::CheckRunner(const SweepSpec& spec, const SweepOptions& o) : s_(std::make_unique<State>()) {
    s_->spec = spec;
    s_->o = o;
    s_->trust_cache = o.cache / "trust";
    fs::create_directories(s_->trust_cache);
}

CheckRunner::~CheckRunner() = default;

CheckOutcome CheckRunner::run(const CheckTask& j, const Config& config, const std::string& key,
                              const std::vector<util::RegressionStream>& rset) {
    const SweepSpec& spec = s_->spec;
    const SweepOptions& o = s_->o;
    if (j.kind == CheckKind::ghdl && (j.stream < 0 || j.stream >= static_cast<int>(rset.size())))
        throw InputError(fmt::format("RTL check of {}: stream {} is not in the regression set ({} streams)", config.name,
                                     j.stream, rset.size()));
    const fs::path rel = fs::path("trust") / config.name;
    const fs::path dir = o.out / rel;
    fs::create_directories(dir);
    CheckOutcome c;
    TrustResult& one = c.one;
    // one cache entry per passed simulator run, a GHDL run's named by its stream (not its
    // place in the set, which another set or an edit of it changes); the gate keeps its
    // own record (vl::run_gate_cached: formats, sources, tools)
    const auto stream_tag = [&] {   // an image stream's entry also names its image's content
        const util::RegressionStream& s = rset[j.stream];
        const std::string image = s.image.empty() ? "" : "-" + util::hex64(util::fnv1a(util::read_file(s.image))).substr(0, 10);
        return fmt::format("{}-{}-{}{}", s.stem(), s.frames, s.idle_every, image);
    };
    const fs::path entry = j.kind == CheckKind::ghdl        ? s_->trust_cache / fmt::format("{}-rtl-{}.json", key, stream_tag())
                           : j.kind == CheckKind::verilator ? s_->trust_cache / (key + "-verilator.json")
                                                            : fs::path();
    if (!entry.empty() && fs::exists(entry)) {
        c.one = trust_from_json(json::parse(util::read_file(entry)));
        c.one.cached = true;
        c.status = "pass";
        return c;
    }
    const auto ts = Clock::now();
    one.ran = true;
    one.runs = 1;
    std::string& status = c.status;
    if (j.kind == CheckKind::gate) {
        gate_check(c, config, o, rel, s_->verilator_m);
    } else if (j.kind == CheckKind::ghdl) {
        ghdl_check(c, config, rset[j.stream], o, rel, dir);
    } else {
        std::call_once(s_->vl_loaded, [&] {
            s_->vl_stream = frames::load_kitti_stream(o.kitti, spec.sequence,
                                                      util::parse_range(spec.trust.verilator_pairs, "trust.verilator_pairs"),
                                                      "sweep spec trust.verilator_pairs '" + spec.trust.verilator_pairs + "'",
                                                      o.threads);
        });
        verilator_check(c, config, s_->vl_stream, o, rel, s_->verilator_m);
    }
    if (j.kind != CheckKind::gate) one.seconds = since(ts);
    if (status != "pass") one.failed = 1;
    else if (!entry.empty()) util::write_file_atomic(entry, trust_to_json(one).dump(2));
    return c;
}

void apply_check(SweepResult& res, const CheckPlan& plan, const CheckTask& j, const CheckOutcome& c, const SweepOptions& o) {
    PointResult& p = res.points.at(j.point);
    TrustResult one = c.one;
    if (one.failed)
        one.detail = fmt::format("{}: {} (log {})",
                                 j.kind == CheckKind::ghdl        ? plan.streams.at(j.stream).pattern + " " + plan.streams.at(j.stream).size()
                                 : j.kind == CheckKind::verilator ? std::string("verilate")
                                                                  : std::string("gate"),
                                 c.status, (o.out / c.log).string());
    add_run(j.kind == CheckKind::ghdl ? p.rtl : j.kind == CheckKind::verilator ? p.verilator : p.gate, one);
    if (j.kind == CheckKind::gate) {
        if (c.gate_cached) ++res.gates_cached;
        else {
            ++res.gates_run;
            res.gate_seconds_sum += one.seconds;
        }
    }
}

void finish_checks(SweepResult& res) {
    for (auto& p : res.points) {
        if (!p.verify) continue;
        if (p.rtl.ran && p.rtl.detail.empty())
            p.rtl.detail = fmt::format("{}/{} streams pass", p.rtl.runs - p.rtl.failed, p.rtl.runs);
        if (p.verilator.ran && p.verilator.detail.empty())
            p.verilator.detail = fmt::format("pairs {} pass", res.spec.trust.verilator_pairs);
    }
}

void check_points(SweepResult& res, const SweepOptions& o) {
    const auto t = Clock::now();
    // ---- 4. RTL checks of the points marked verify ------------------------------------
    const CheckPlan plan = plan_checks(res, o);
    if (!plan.tasks.empty()) {
        CheckRunner runner(res.spec, o);
        std::vector<CheckOutcome> outcomes(plan.tasks.size());
        std::atomic<int> tdone{0};
        run_pool(plan.tasks.size(), o.jobs, [&](size_t k) {
            const CheckTask& j = plan.tasks[k];
            const PointResult& p = res.points[j.point];
            outcomes[k] = runner.run(j, p.config, plan.keys[j.point], plan.streams);
            const CheckOutcome& c = outcomes[k];
            progress(o.progress,
                     fmt::format("[rtl {}/{}] {} {}: {} ({:.0f} s{})", ++tdone, plan.tasks.size(), p.config.name,
                                 j.kind == CheckKind::ghdl ? "ghdl " + plan.streams[j.stream].pattern + " " + plan.streams[j.stream].size()
                                 : j.kind == CheckKind::verilator ? "verilator " + res.spec.trust.verilator_pairs
                                                                  : std::string("three-way gate"),
                                 c.status, c.one.seconds,
                                 c.gate_cached ? ", verdict recorded earlier" : c.one.cached ? ", cached" : ""));
        });
        // in the plan's order, whatever order they finished in
        for (size_t k = 0; k < plan.tasks.size(); ++k) apply_check(res, plan, plan.tasks[k], outcomes[k], o);
        finish_checks(res);
    }
    res.seconds_trust = since(t);
}

}  // namespace hc::sweep
