// sweep.cpp: see sweep.hpp. Phases, each parallel over the cores:
//   1. frames + OpenCV reference masks (once for all configurations)
//   2. cost: synthesis of every configuration, `jobs` at a time (cache hits instant);
//      derived ranges of every configuration (ranges.hpp), cached by the synthesis key
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
#include "frames/frames.hpp"
#include "regress/golden.hpp"
#include "model/harris/formats_json.hpp"
#include "util/util.hpp"
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

json trust_json(const TrustResult& t) {
    return {{"runs", t.runs}, {"failed", t.failed}, {"mismatches", t.mismatches}, {"reads", t.reads},
            {"seconds", t.seconds}, {"detail", t.detail}};
}
TrustResult trust_from_json(const json& j) {
    TrustResult t;
    t.ran = true;
    t.cached = true;
    t.runs = j.at("runs");
    t.failed = j.at("failed");
    t.mismatches = j.at("mismatches");
    t.reads = j.at("reads");
    t.seconds = j.at("seconds");
    t.detail = j.at("detail");
    return t;
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
        } catch (const landmarks::InputError& e) {
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
    std::vector<const Image*> frames;
    for (const auto& f : stream.frames) frames.push_back(&f);
    // scored frames: all but the first stereo pair, which only seeds the threshold
    auto scored = [&](size_t k) { return stream.pair_index[k] != stream.pair_index.front(); };
    for (size_t k = 0; k < frames.size(); ++k) res.scored_frames += scored(k);

    res.points.resize(n);
    for (size_t i = 0; i < n; ++i) {
        res.points[i].config = spec.configs[which[i]];
        res.points[i].register_bits = datapath_register_bits(res.points[i].config.formats, spec.cost_geometry);
    }
    // ---- 2. cost -----------------------------------------------------------------------
    t = Clock::now();
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

    // ---- 2b. derived ranges, cached under the synthesis key -------------------------
    for (size_t i = 0; i < n; ++i) {
        PointResult& p = res.points[i];
        p.ranges = cached_ranges(p.config.formats, p.cost.key, o.cache / "ranges");
        p.has_ranges = true;
        progress(o.progress, fmt::format("[ranges {}/{}] {}: {} ({})", i + 1, n, p.config.name, p.ranges.summary(),
                                         p.ranges.cached ? "cached" : fmt::format("{:.2f} s", p.ranges.seconds_interval +
                                                                                                  p.ranges.seconds_search)));
    }

    // ---- 3. accuracy and overflow ------------------------------------------------------
    t = Clock::now();
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
            if (scored(k)) p.accuracy.add(eval::classify(run.masks[k], ref[k]));
        p.eval_seconds = since(tb);
        progress(o.progress, fmt::format("[accuracy {}/{}] {}: recall {:.4f} precision {:.4f} F1 {:.4f}{} ({:.1f} s + audit {:.1f} s)",
                                         i + 1, n, p.config.name, p.accuracy.recall(), p.accuracy.precision(), p.accuracy.f1(),
                                         p.wraps ? " WRAPS: " + p.overflow.summary() : "", p.eval_seconds, p.overflow_seconds));
    }
    res.seconds_accuracy = since(t);

    // ---- 3b. downstream: correct stereo matches of the landmark chain -------------------
    t = Clock::now();
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
    mark_pareto(res.points);
    mark_verify(res);
    check_points(res, o);
    res.seconds_total = since(t0);
    return res;
}

void check_points(SweepResult& res, const SweepOptions& o) {
    const SweepSpec& spec = res.spec;
    const size_t n = res.points.size();
    std::mutex m;
    auto t = Clock::now();
    // ---- 4. RTL checks of the points marked verify ------------------------------------
    if (o.trust && (spec.trust.rtl || !spec.trust.verilator_pairs.empty() || spec.trust.verilator_gate)) {
        CostOptions co;
        co.rtl_sources = cosim::rtl_sources();
        co.cache_dir = o.cache / "synth";
        co.geometry = spec.cost_geometry;
        const CostContext ctx(co);
        const fs::path trust_cache = o.cache / "trust";
        fs::create_directories(trust_cache);
        const auto rset = util::read_regression_set(o.regression_set);
        // the RTL checks depend on the RTL, the tool versions and the formats: same key basis
        struct TJob { size_t point; int stream; };   // stream -1: Verilator, -2: the gate
        std::vector<TJob> tj;
        std::vector<std::string> keys(n);
        for (size_t i = 0; i < n; ++i) {
            if (!res.points[i].verify) continue;
            keys[i] = util::hex64(util::fnv1a(ctx.fingerprint + fields_text(res.points[i].config.formats, format_fields()) +
                                              fmt::format("|{}|{}|{}", spec.trust.verilator_pairs,
                                                          spec.trust.verilator_gate, spec.sequence)));
            const fs::path cfg = o.out / "configs" / (res.points[i].config.name + ".json");
            util::write_file_atomic(cfg, formats_to_json(res.points[i].config.formats, res.points[i].config.name));
            auto& p = res.points[i];
            // one cache entry per passed simulator run, written as soon as it passes, so an
            // interrupted sweep keeps what it finished
            if (spec.trust.rtl)
                for (int st = 0; st < static_cast<int>(rset.size()); ++st) {
                    const fs::path c = trust_cache / fmt::format("{}-rtl-{}.json", keys[i], st);
                    if (fs::exists(c)) add_run(p.rtl, trust_from_json(json::parse(util::read_file(c))));
                    else tj.push_back({i, st});
                }
            // the gate keeps its own record (vl::run_gate_cached: formats, sources, tools)
            if (spec.trust.verilator_gate) tj.push_back({i, -2});
            if (!spec.trust.verilator_pairs.empty()) {
                const fs::path c = trust_cache / (keys[i] + "-verilator.json");
                if (fs::exists(c)) add_run(p.verilator, trust_from_json(json::parse(util::read_file(c))));
                else tj.push_back({i, -1});
            }
        }
        // the Verilator runs' frames: the KITTI pairs of the trust spec, loaded once
        frames::Stream vl_stream;
        if (!spec.trust.verilator_pairs.empty())
            vl_stream = frames::load_kitti_stream(o.kitti, spec.sequence,
                                                  util::parse_range(spec.trust.verilator_pairs, "trust.verilator_pairs"),
                                                  "sweep spec trust.verilator_pairs '" + spec.trust.verilator_pairs + "'",
                                                  o.threads);
        // gates, then Verilator runs first: they are the longest (netlist builds)
        std::stable_sort(tj.begin(), tj.end(), [](const TJob& a, const TJob& b) { return std::min(a.stream, 0) < std::min(b.stream, 0); });
        std::atomic<int> tdone{0};
        std::mutex verilator_m;   // one verilated design at a time (Verilator's runtime is process-global)
        run_pool(tj.size(), o.jobs, [&](size_t k) {
            const TJob& j = tj[k];
            PointResult& p = res.points[j.point];
            const std::string name = p.config.name;
            const fs::path dir = o.out / "trust" / name;
            fs::create_directories(dir);
            const auto ts = Clock::now();
            TrustResult one;
            one.ran = true;
            one.runs = 1;
            std::string status;
            fs::path log;
            bool gate_cached = false;
            if (j.stream == -2) {
                log = dir / "gate.log";
                std::ofstream glog(log);
                std::string why;
                if (!vl::toolchain_available(&why)) {
                    status = "no gate: " + why;
                } else {
                    try {
                        std::lock_guard<std::mutex> l(verilator_m);
                        const vl::GateResult g =
                            vl::run_gate_cached(p.config.formats, {}, vl::default_cache_dir(), glog, &gate_cached);
                        one.reads = g.reads;
                        one.cached = gate_cached;
                        status = g.verdict == vl::GateVerdict::pass ? "pass" : std::string(vl::verdict_name(g.verdict)) + ": " + g.first;
                        one.detail = g.verdict == vl::GateVerdict::pass
                                         ? fmt::format("pass: {} writes, {} reads agree three ways ({:.0f} s{})", g.writes,
                                                       g.reads, g.seconds, gate_cached ? ", recorded" : "")
                                         : std::string();
                        one.seconds = g.seconds;
                    } catch (const SimulatorError& e) {
                        status = e.what();
                    }
                }
            } else if (j.stream >= 0) {
                const util::RegressionStream& s = rset[j.stream];
                const std::string tag = fmt::format("rtl-{}-{}-{}", s.pattern, s.size(), s.idle_every);
                log = dir / (tag + ".log");
                fs::remove(log);
                cosim::GhdlRun run;
                run.frames = regress::stream_frames(s);
                for (int f = 0; f < s.frames; ++f) run.frame_names.push_back(s.pattern + "#" + std::to_string(f));
                run.formats = p.config.formats;
                run.backend = o.ghdl_backend;
                run.keep_going = true;
                run.idle_every = s.idle_every;
                run.progress = false;
                run.log = log;
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
            } else {
                log = dir / "verilate.log";
                fs::remove(log);
                vl::VerilateRun run;
                run.frames = vl_stream.frames;
                run.frame_names = vl_stream.names;
                run.formats = p.config.formats;
                run.gate = false;   // the gate is its own check (stream -2)
                run.keep_going = true;
                std::ofstream vlog(log);
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
            if (j.stream != -2) one.seconds = since(ts);
            if (status != "pass") {
                one.failed = 1;
                one.detail = fmt::format("{}: {} (log {})", j.stream >= 0 ? rset[j.stream].pattern + " " + rset[j.stream].size()
                                                          : j.stream == -1 ? "verilate" : "gate",
                                         status, log.string());
            } else if (j.stream != -2) {
                const std::string entry = j.stream >= 0 ? fmt::format("{}-rtl-{}.json", keys[j.point], j.stream)
                                                        : keys[j.point] + "-verilator.json";
                util::write_file_atomic(trust_cache / entry, trust_json(one).dump(2));
            }
            {
                std::lock_guard<std::mutex> l(m);
                add_run(j.stream >= 0 ? p.rtl : j.stream == -1 ? p.verilator : p.gate, one);
                if (j.stream == -2) {
                    if (gate_cached) ++res.gates_cached;
                    else {
                        ++res.gates_run;
                        res.gate_seconds_sum += one.seconds;
                    }
                }
            }
            progress(o.progress, fmt::format("[rtl {}/{}] {} {}: {} ({:.0f} s{})", ++tdone, tj.size(), name,
                                             j.stream >= 0 ? "ghdl " + rset[j.stream].pattern + " " + rset[j.stream].size()
                                             : j.stream == -1 ? "verilator " + spec.trust.verilator_pairs : "three-way gate",
                                             status, one.seconds, gate_cached ? ", verdict recorded earlier" : ""));
        });
        for (auto& p : res.points) {
            if (!p.verify) continue;
            if (p.rtl.ran && p.rtl.detail.empty())
                p.rtl.detail = fmt::format("{}/{} streams pass", p.rtl.runs - p.rtl.failed, p.rtl.runs);
            if (p.verilator.ran && p.verilator.detail.empty())
                p.verilator.detail = fmt::format("pairs {} pass", spec.trust.verilator_pairs);
        }
    }
    res.seconds_trust = since(t);
}

}  // namespace hc::sweep
