// sweep.cpp: see sweep.hpp. Phases, each parallel over the cores:
//   1. frames + OpenCV reference masks (once for all configurations)
//   2. cost: synthesis of every configuration, `jobs` at a time (cache hits instant)
//   3. accuracy and overflow audit per configuration (frames in parallel, TBB)
//   4. Pareto front; RTL checks of its points, `jobs` simulator processes at a time
//      (results cached like the synthesis: an unchanged point is not simulated again)
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

#include "frames.hpp"
#include "process.hpp"
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

std::pair<int, int> parse_pairs(const std::string& s, const std::string& what) {
    if (s.empty()) return {0, 1 << 30};
    const auto c = s.find(':');
    try {
        if (c == std::string::npos) throw std::invalid_argument(s);
        const int a = c == 0 ? 0 : std::stoi(s.substr(0, c));
        const int b = c + 1 == s.size() ? (1 << 30) : std::stoi(s.substr(c + 1));
        if (a < 0 || b <= a) throw std::invalid_argument(s);
        return {a, b};
    } catch (const std::exception&) {
        throw tools::InputError(what + " '" + s + "' is not a stereo pair range a:b with 0 <= a < b");
    }
}

/// The evaluation stream L0 R0 L1 R1 ... of a KITTI sequence (as `harris-cosim eval`).
eval::Stream load_stream(const fs::path& kitti, const std::string& seq, const std::string& pairs, int threads) {
    const auto [first, last] = parse_pairs(pairs, "data.pairs");
    const tools::KittiSequence k = tools::open_kitti(kitti, seq);
    const auto paths = tools::stereo_stream(k, first, last);
    if (paths.size() < 4)
        throw tools::InputError(fmt::format("KITTI sequence '{}' pairs {} give {} frames; the evaluation needs at least 2 stereo pairs",
                                            k.root.string(), pairs.empty() ? "all" : pairs, paths.size()));
    eval::Stream s;
    s.frames.resize(paths.size());
    std::vector<std::string> errors(paths.size());
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(size_t{0}, paths.size(), [&](size_t i) {
            try {
                s.frames[i] = tools::load_image(paths[i]);
            } catch (const std::exception& e) {
                errors[i] = e.what();
            }
        });
    });
    for (const auto& e : errors)
        if (!e.empty()) throw tools::InputError(e);
    for (size_t i = 0; i < paths.size(); ++i) {
        if (s.frames[i].width != s.frames[0].width || s.frames[i].height != s.frames[0].height)
            throw tools::InputError("image '" + paths[i].string() + "' differs in size from '" + paths[0].string() + "'");
        s.names.push_back(seq + "/" + (i % 2 ? "R" : "L") + paths[i].stem().string());
        s.pair_index.push_back(first + static_cast<int>(i / 2));
    }
    s.description = fmt::format("KITTI sequence {} ({}), stereo pairs {}..{}: {} frames {}x{}", seq, k.root.string(), first,
                                first + static_cast<int>(paths.size() / 2) - 1, paths.size(), s.frames[0].width,
                                s.frames[0].height);
    return s;
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

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// One line of golden/regression-set.txt: pattern, size, frames, idle_every.
struct Stream1 {
    std::string pattern, size;
    int frames = 0, idle_every = 0;
};
std::vector<Stream1> regression_set(const fs::path& p) {
    std::ifstream in(p);
    if (!in) throw tools::InputError("regression set '" + p.string() + "' cannot be read");
    std::vector<Stream1> v;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ss(line);
        Stream1 s;
        if (ss >> s.pattern >> s.size >> s.frames >> s.idle_every) v.push_back(s);
    }
    if (v.empty()) throw tools::InputError("regression set '" + p.string() + "' has no stream");
    return v;
}

std::uint64_t fnv1a(const std::string& s) {
    std::uint64_t h = 1469598103934665603ULL;
    for (unsigned char c : s) {
        h ^= c;
        h *= 1099511628211ULL;
    }
    return h;
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

SweepResult run_sweep(const SweepOptions& o) {
    const auto t0 = Clock::now();
    SweepResult res;
    res.spec = load_sweep_spec(o.spec_file);   // std::invalid_argument -> status 2
    const SweepSpec& spec = res.spec;
    const size_t n = spec.configs.size();
    progress(o.progress, fmt::format("{} configurations from {}", n, o.spec_file.string()));
    for (const auto& note : spec.notes) progress(o.progress, "note: " + note);
    cv::setNumThreads(1);   // frames run in parallel; OpenCV's own threads would oversubscribe

    // ---- 1. frames and reference -------------------------------------------------------
    auto t = Clock::now();
    const eval::Stream stream = load_stream(o.kitti, spec.sequence, spec.pairs, o.threads);
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
        res.points[i].config = spec.configs[i];
        res.points[i].register_bits = datapath_register_bits(spec.configs[i].formats, spec.cost_geometry);
    }

    // ---- 2. cost -----------------------------------------------------------------------
    t = Clock::now();
    CostOptions co;
    co.rtl_dir = o.source_dir / "rtl";
    co.rtl_order = o.rtl_order;
    co.cache_dir = o.cache / "synth";
    co.geometry = spec.cost_geometry;
    const CostContext ctx(co);
    struct Job { size_t point; Variant v; };
    std::vector<Job> jobs;
    for (size_t i = 0; i < n; ++i) {
        jobs.push_back({i, Variant::signed_mul});
        if (spec.configs[i].formats == Formats{}) jobs.push_back({i, Variant::ghdl});   // the DSP note
    }
    std::atomic<int> done{0};
    std::mutex m;
    run_pool(jobs.size(), o.jobs, [&](size_t k) {
        const Job& j = jobs[k];
        const Cost c = synth_cost(ctx, spec.configs[j.point].formats, j.v);
        {
            std::lock_guard<std::mutex> l(m);
            PointResult& p = res.points[j.point];
            if (j.v == Variant::signed_mul) p.cost = c;
            else { p.cost_ghdl = c; p.has_cost_ghdl = true; }
            if (c.cached) ++res.synth_cached;
            else { ++res.synthesised; res.synth_seconds_sum += c.seconds; }
        }
        progress(o.progress, fmt::format("[cost {}/{}] {} ({}): {} LUT, {} FF, {} DSP, {} CARRY4 {}", ++done, jobs.size(),
                                         spec.configs[j.point].name, variant_name(j.v), c.luts, c.ffs, c.dsps, c.carry4,
                                         c.cached ? "(cached)" : fmt::format("({:.0f} s)", c.seconds)));
    });
    res.seconds_cost = since(t);

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

    // ---- 4. Pareto front and its RTL checks --------------------------------------------
    mark_pareto(res.points);
    mark_verify(res);
    t = Clock::now();
    if (o.trust && (spec.trust.rtl || !spec.trust.verilator_pairs.empty())) {
        const fs::path trust_cache = o.cache / "trust";
        fs::create_directories(trust_cache);
        const auto rset = regression_set(o.source_dir / "golden" / "regression-set.txt");
        // the RTL checks depend on the RTL, the tool versions and the formats: same key basis
        struct TJob { size_t point; int stream; };   // stream -1: Verilator
        std::vector<TJob> tj;
        std::vector<std::string> keys(n);
        for (size_t i = 0; i < n; ++i) {
            if (!res.points[i].verify) continue;
            keys[i] = fmt::format("{:016x}", fnv1a(ctx.fingerprint + formats_json(res.points[i].config.formats, "") +
                                                    fmt::format("{}|{}|{}", spec.trust.verilator_pairs,
                                                                spec.trust.verilator_gate, spec.sequence)));
            const fs::path cfg = o.out / "configs" / (res.points[i].config.name + ".json");
            fs::create_directories(cfg.parent_path());
            tools::write_file_atomic(cfg, formats_json(res.points[i].config.formats, res.points[i].config.name));
            auto& p = res.points[i];
            // one cache entry per passed simulator run, written as soon as it passes, so an
            // interrupted sweep keeps what it finished
            if (spec.trust.rtl)
                for (int st = 0; st < static_cast<int>(rset.size()); ++st) {
                    const fs::path c = trust_cache / fmt::format("{}-rtl-{}.json", keys[i], st);
                    if (fs::exists(c)) add_run(p.rtl, trust_from_json(json::parse(read_text(c))));
                    else tj.push_back({i, st});
                }
            if (!spec.trust.verilator_pairs.empty()) {
                const fs::path c = trust_cache / (keys[i] + "-verilator.json");
                if (fs::exists(c)) add_run(p.verilator, trust_from_json(json::parse(read_text(c))));
                else tj.push_back({i, -1});
            }
        }
        // Verilator runs first: they are the longest (netlist builds, gate)
        std::stable_sort(tj.begin(), tj.end(), [](const TJob& a, const TJob& b) { return (a.stream < 0) > (b.stream < 0); });
        std::atomic<int> tdone{0};
        run_pool(tj.size(), o.jobs, [&](size_t k) {
            const TJob& j = tj[k];
            PointResult& p = res.points[j.point];
            const std::string name = p.config.name;
            const fs::path dir = o.out / "trust" / name;
            fs::create_directories(dir);
            const fs::path cfg = o.out / "configs" / (name + ".json");
            std::vector<std::string> argv{o.self.string()};
            fs::path summary, log;
            if (j.stream >= 0) {
                const Stream1& s = rset[j.stream];
                const std::string tag = fmt::format("rtl-{}-{}-{}", s.pattern, s.size, s.idle_every);
                summary = dir / (tag + ".json");
                log = dir / (tag + ".log");
                argv.insert(argv.end(), {"rtl", "--pattern", s.pattern, "--size", s.size, "--frames", std::to_string(s.frames),
                                         "--idle-every", std::to_string(s.idle_every), "--config", cfg.string(),
                                         "--keep-going", "--quiet", "--vcd", (dir / (tag + ".vcd")).string(), "--json", summary.string()});
                if (!o.sim_dir.empty()) argv.insert(argv.end(), {"--sim-dir", o.sim_dir});
            } else {
                summary = dir / "verilate.json";
                log = dir / "verilate.log";
                argv.insert(argv.end(), {"verilate", "--kitti", o.kitti.string(), "--sequence", spec.sequence, "--pairs",
                                         spec.trust.verilator_pairs, "--config", cfg.string(), "--keep-going", "--json",
                                         summary.string()});
                if (!spec.trust.verilator_gate) argv.push_back("--no-gate");
            }
            fs::remove(summary);
            fs::remove(log);
            const auto ts = Clock::now();
            const int rc = tools::run_process(argv, {}, log.string());
            const double secs = since(ts);
            long mism = 0, reads = 0;
            std::string status = fmt::format("exit {}", rc);
            if (fs::exists(summary)) {
                try {
                    const json js = json::parse(read_text(summary));
                    if (j.stream >= 0) mism = js.at("mismatches").at("cycles").get<long>() + js.value("read_mismatches", 0L);
                    else mism = js.contains("mismatches") ? js["mismatches"].value("writes", 0L) : 0;
                    reads = js.value("reads", 0L);
                    if (js.contains("status")) status = js["status"].get<std::string>();
                } catch (const std::exception& e) {
                    status = std::string("unreadable summary: ") + e.what();
                }
            }
            TrustResult one;
            one.ran = true;
            one.runs = 1;
            one.mismatches = mism;
            one.reads = reads;
            one.seconds = secs;
            if (rc != 0) {
                one.failed = 1;
                one.detail = fmt::format("{}: {} (log {})", j.stream >= 0 ? rset[j.stream].pattern + " " + rset[j.stream].size : "verilate",
                                         status, log.string());
            } else {
                const std::string entry = j.stream >= 0 ? fmt::format("{}-rtl-{}.json", keys[j.point], j.stream)
                                                        : keys[j.point] + "-verilator.json";
                tools::write_file_atomic(trust_cache / entry, trust_json(one).dump(2));
            }
            {
                std::lock_guard<std::mutex> l(m);
                add_run(j.stream >= 0 ? p.rtl : p.verilator, one);
            }
            progress(o.progress, fmt::format("[rtl {}/{}] {} {}: {} ({:.0f} s)", ++tdone, tj.size(), name,
                                             j.stream >= 0 ? "ghdl " + rset[j.stream].pattern + " " + rset[j.stream].size : "verilator " + spec.trust.verilator_pairs,
                                             rc == 0 ? "pass" : status, secs));
        });
        for (auto& p : res.points) {
            if (!p.verify) continue;
            if (p.rtl.ran && p.rtl.detail.empty())
                p.rtl.detail = fmt::format("{}/{} streams pass", p.rtl.runs - p.rtl.failed, p.rtl.runs);
            if (p.verilator.ran && p.verilator.detail.empty())
                p.verilator.detail = fmt::format("pairs {} pass{}", spec.trust.verilator_pairs,
                                                 spec.trust.verilator_gate ? " (gate passed)" : " (no gate: Verilator not cross-checked against GHDL)");
        }
    }
    res.seconds_trust = since(t);
    res.seconds_total = since(t0);
    return res;
}

}  // namespace hc::sweep
