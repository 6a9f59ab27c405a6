// cmd_eval.cpp: `harris-cosim eval`, the thesis's precision/recall evaluation against
// OpenCV's Harris (section 6.3.2), with the ablation of each approximation and, for the
// cycle source, the deviation catalog of docs/deviations.md. Protocol and metrics:
// docs/metrics.md; outputs: tools/eval/report.hpp.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "commands.hpp"
#include "driver/host_driver.hpp"
#include "gate.hpp"
#include "lockstep.hpp"
#include "netlist.hpp"
#include "eval/eval.hpp"
#include "eval/report.hpp"
#include "frames.hpp"

namespace fs = std::filesystem;

namespace hc::tools {

namespace {

struct EvalOptions {
    std::string kitti, sequence = "01", source = "spec", out = "eval-report", frames, overlay, data;
    int threads = 0;
    bool ablation = true;
};

std::pair<int, int> parse_range(const std::string& s) {
    if (s.empty()) return {0, 1 << 30};
    const auto c = s.find(':');
    try {
        if (c == std::string::npos) throw std::invalid_argument(s);
        const int a = c == 0 ? 0 : std::stoi(s.substr(0, c));
        const int b = c + 1 == s.size() ? (1 << 30) : std::stoi(s.substr(c + 1));
        if (a < 0 || b <= a) throw std::invalid_argument(s);
        return {a, b};
    } catch (const std::exception&) {
        throw InputError("--frames '" + s + "' is not a stereo pair range a:b with 0 <= a < b");
    }
}

std::vector<int> parse_list(const std::string& s) {
    std::vector<int> v;
    std::stringstream ss(s);
    std::string tok;
    while (std::getline(ss, tok, ',')) {
        try {
            v.push_back(std::stoi(tok));
        } catch (const std::exception&) {
            throw InputError("--overlay '" + s + "' is not a comma-separated list of frame numbers");
        }
    }
    return v;
}

// The default stream of a machine without KITTI: pairs of consecutive frames of OpenCV's
// sample video vtest.avi (opencv-doc), grey, centred 640x360 crop (the thesis's camera
// size); without opencv-doc, the synthetic `blocks` pattern.
eval::Stream default_stream(int first, int last) {
    eval::Stream s;
    const std::string video = "/usr/share/doc/opencv-doc/examples/data/vtest.avi";
    const int pairs = std::min(last, 12) - first;
    if (pairs <= 0) throw InputError("--frames selects no pair of the default 12-pair stream");
    cv::VideoCapture cap;
    if (fs::exists(video) && cap.open(video)) {
        cv::Mat f, g;
        for (int k = 0; k < 2 * std::min(last, 12) && cap.read(f); ++k) {
            if (k < 2 * first) continue;
            cv::cvtColor(f, g, cv::COLOR_BGR2GRAY);
            Image im(g.cols, g.rows);
            for (int r = 0; r < g.rows; ++r) std::copy_n(g.ptr<std::uint8_t>(r), g.cols, &im.at(r, 0));
            s.frames.push_back(crop(im, 640, 360, video));
            s.names.push_back(fmt::format("vtest/{}{:03}", k % 2 ? 'R' : 'L', k / 2));
            s.pair_index.push_back(k / 2);
        }
        s.description = fmt::format("default stream: {} frame pairs of {} (grey, 640x360 centre crop); no KITTI data found",
                                    s.frames.size() / 2, video);
    }
    if (s.frames.size() < 4) {
        s = {};
        for (int k = 2 * first; k < 2 * (first + pairs); ++k) {
            s.frames.push_back(make_pattern(Pattern::blocks, 640, 360, k));
            s.names.push_back(fmt::format("blocks/{}{:03}", k % 2 ? 'R' : 'L', k / 2));
            s.pair_index.push_back(k / 2);
        }
        s.description = "default stream: generated 'blocks' pattern 640x360 (no KITTI data, no opencv-doc video)";
    }
    return s;
}

eval::Stream kitti_stream(const fs::path& dir, const std::string& seq, int first, int last, int threads) {
    const KittiSequence k = open_kitti(dir, seq);
    const auto paths = stereo_stream(k, first, last);
    if (paths.size() < 4)
        throw InputError(fmt::format("KITTI sequence '{}' pairs {}..{} give {} frames; the evaluation needs at least 2 stereo pairs",
                                     k.root.string(), first, last - 1, paths.size()));
    eval::Stream s;
    s.frames.resize(paths.size());
    std::vector<std::string> errors(paths.size());
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(size_t{0}, paths.size(), [&](size_t i) {
            try {
                s.frames[i] = load_image(paths[i]);
            } catch (const std::exception& e) {
                errors[i] = e.what();
            }
        });
    });
    for (const auto& e : errors)
        if (!e.empty()) throw InputError(e);
    for (size_t i = 0; i < paths.size(); ++i) {
        if (s.frames[i].width != s.frames[0].width || s.frames[i].height != s.frames[0].height)
            throw InputError("image '" + paths[i].string() + "' differs in size from '" + paths[0].string() + "'");
        s.names.push_back(seq + "/" + (i % 2 ? "R" : "L") + paths[i].stem().string());
        s.pair_index.push_back(first + static_cast<int>(i / 2));
    }
    s.description = fmt::format("KITTI {} sequence {}, stereo pairs {}..{} ({} frames, {}x{})", dir.string(), seq,
                                first, first + static_cast<int>(paths.size() / 2) - 1, paths.size(),
                                s.frames[0].width, s.frames[0].height);
    return s;
}

/// The RTL as a corner source: the GHDL-synthesised netlist under Verilator (trusted only
/// after its GHDL/Verilator/model gate passes), streamed exactly like the cycle model; the
/// masks come from the corner bits the netlist returns on every read. `mismatches` counts
/// reads where the netlist and the cycle model (run in lock step) disagree.
eval::SourceRun run_rtl_source(const eval::Stream& stream, long& mismatches) {
    const auto t0 = std::chrono::steady_clock::now();
    const Formats f{};
    const fs::path cache = vl::default_cache_dir();
    bool cached = false;
    const vl::GateResult gate = vl::run_gate_cached(f, {}, cache, std::cerr, &cached);
    if (gate.verdict != vl::GateVerdict::pass)
        throw std::runtime_error("--source rtl: the GHDL/Verilator/model gate did not pass (" +
                                 std::string(vl::verdict_name(gate.verdict)) + "): " + gate.first);
    const Geometry g{stream.frames[0].width, stream.frames[0].height};
    const vl::NetlistConfig nc{g, f, false, {}};
    const fs::path so = vl::build_netlist(nc, cache, std::cerr);
    vl::VerilatedDesign dut(so, vl::config_key(nc));
    std::vector<const Image*> ptrs;
    for (const auto& im : stream.frames) ptrs.push_back(&im);
    std::vector<std::string> rows;
    vl::RunOptions opt;
    opt.keep_going = true;
    opt.read_rows = &rows;
    const int n = static_cast<int>(stream.frames.size());
    opt.on_frame = [&](const vl::FrameStats& s) {
        std::fprintf(stderr, "eval: rtl frame %d/%d: %ld reads, %ld corners, %ld mismatches\n", s.index + 1, n,
                     s.reads, s.corners, s.mismatches);
    };
    const vl::RunResult rr = vl::run_lockstep(g, f, dut, ptrs, stream.names, opt);
    mismatches = rr.mismatches;
    eval::SourceRun run;
    const size_t npix = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
    run.masks.assign(static_cast<size_t>(n), std::vector<std::uint8_t>(npix, 0));
    run.thr.assign(static_cast<size_t>(n), -1);   // not observed on the netlist (no obs port)
    run.max.assign(static_cast<size_t>(n), -1);
    const HostDriver drv(g, ptrs);
    std::vector<Corner> cs;
    for (const auto& row : rows) {   // write,frame,x,y,value
        long w = 0;
        int frame = 0, x = 0, y = 0;
        unsigned value = 0;
        if (std::sscanf(row.c_str(), "%ld,%d,%d,%d,%u", &w, &frame, &x, &y, &value) != 5 || frame < 0 || frame >= n)
            throw std::runtime_error("--source rtl: unreadable read row '" + row + "'");
        cs.clear();
        drv.decode(ReadPos{frame, x, y}, value, cs);
        for (const Corner& c : cs) run.masks[static_cast<size_t>(c.frame)][static_cast<size_t>(c.y) * g.width + c.x] = 1;
    }
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return run;
}

void run_eval(const EvalOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    const eval::Source source = [&] {
        try {
            return eval::parse_source(o.source);
        } catch (const std::invalid_argument& e) {
            throw InputError(e.what());
        }
    }();
    if (source == eval::Source::rtl) {
        std::string why;
        if (!vl::toolchain_available(&why)) throw InputError("--source rtl needs GHDL and Verilator: " + why);
    }
    const auto [first, last] = parse_range(o.frames);
    const std::vector<int> overlays = parse_list(o.overlay);
    cv::setNumThreads(1);   // frames run in parallel; OpenCV's own threads would oversubscribe

    // ---- frames ------------------------------------------------------------------------
    std::fprintf(stderr, "eval: loading frames...\n");
    eval::Stream stream;
    fs::path kitti_dir;
    if (!o.kitti.empty()) {
        kitti_dir = o.kitti;
    } else if (auto d = data_dir(o.data); d && fs::is_directory(*d / "kitti")) {
        kitti_dir = *d / "kitti";
    }
    if (!kitti_dir.empty()) stream = kitti_stream(kitti_dir, o.sequence, first, last, o.threads);
    else stream = default_stream(first, last);
    const int n = static_cast<int>(stream.frames.size());
    for (int f : overlays)
        if (f < 0 || f >= n) throw InputError(fmt::format("--overlay frame {} is not in the stream (0..{})", f, n - 1));
    fs::create_directories(o.out);
    std::fprintf(stderr, "eval: %s\n", stream.description.c_str());

    // ---- reference ---------------------------------------------------------------------
    std::fprintf(stderr, "eval: OpenCV reference on %d frames...\n", n);
    const double tr0 = secs();
    const auto ref = eval::run_reference(stream, spec::ReferenceOptions{}, o.threads);
    const double t_ref = secs() - tr0;

    // ---- source ------------------------------------------------------------------------
    std::fprintf(stderr, "eval: %s source...\n", eval::source_name(source).c_str());
    eval::SourceRun run;
    eval::CycleRun cyc;
    long rtl_mismatches = 0;
    if (source == eval::Source::spec) {
        run = eval::run_spec(stream, spec::Options{}, o.threads);
    } else if (source == eval::Source::rtl) {
        run = run_rtl_source(stream, rtl_mismatches);
    } else {
        cyc = eval::run_cycle(stream, Formats{}, true);
        run = cyc;
    }
    // scoring: drop the first pair (threshold seed) and, for the cycle model, the last
    // (its last windows are read only while a next pair is written)
    const int last_pair = stream.pair_index.back();
    auto scored = [&](int k) {
        return stream.pair_index[k] != stream.pair_index.front() &&
               (source == eval::Source::spec || stream.pair_index[k] != last_pair);
    };
    eval::Report rep;
    rep.source = eval::source_name(source);
    rep.stream = stream.description;
    rep.threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
    rep.command = fmt::format("harris-cosim eval --source {}{}{} --out {}", o.source,
                              kitti_dir.empty() ? "" : " --kitti " + kitti_dir.string() + " --sequence " + o.sequence,
                              o.frames.empty() ? "" : " --frames " + o.frames, o.out);
    rep.seconds_source = run.seconds;
    if (source == eval::Source::rtl)
        rep.notes.push_back(fmt::format(
            "RTL source: GHDL-synthesised netlist under Verilator (gate passed), {} reads disagreeing with the "
            "cycle model run in lock step; the thr/max columns are not observed on the netlist (-1).",
            rtl_mismatches));
    rep.seconds_reference = t_ref;
    for (int k = 0; k < n; ++k) {
        eval::FrameRow row;
        row.frame = k;
        row.name = stream.names[k];
        row.pair = stream.pair_index[k];
        row.scored = scored(k);
        row.c = eval::classify(run.masks[k], ref[k]);
        row.source_corners = spec::count_corners(run.masks[k]);
        row.reference_corners = spec::count_corners(ref[k]);
        row.thr = run.thr[k];
        row.max = run.max[k];
        if (row.scored) rep.total.add(row.c);
        rep.frames.push_back(row);
    }

    // ---- ablation (spec model) ---------------------------------------------------------
    if (o.ablation) {
        std::fprintf(stderr, "eval: ablation...\n");
        struct V { std::string name; spec::Options opt; };
        std::vector<V> vs;
        spec::Options base;
        vs.push_back({"none: thesis spec model", base});
        { auto x = base; x.k = spec::KRule::exact; vs.push_back({"k = 0.04 exactly", x}); }
        { auto x = base; x.thr = spec::ThrRule::exact; vs.push_back({"threshold 0.01 x max exactly", x}); }
        { auto x = base; x.formats = spec::Options::untruncated(); vs.push_back({"no truncation in M and block sum", x}); }
        { auto x = base; x.max_from = spec::MaxFrom::current; vs.push_back({"current-frame maximum", x}); }
        { auto x = base; x.nms = spec::Nms::non_strict; vs.push_back({"non-strict NMS (== dilate)", x}); }
        { auto x = base; x.border = spec::Border::reflect101; vs.push_back({"OpenCV border (reflect-101)", x}); }
        {
            spec::Options x;
            x.k = spec::KRule::exact; x.thr = spec::ThrRule::exact; x.formats = spec::Options::untruncated();
            x.max_from = spec::MaxFrom::current; x.nms = spec::Nms::non_strict; x.border = spec::Border::reflect101;
            vs.push_back({"all of the above together", x});
        }
        for (const auto& v : vs) {
            const auto r = eval::run_spec(stream, v.opt, o.threads);
            eval::AblationRow a{v.name, v.opt.describe(), {}};
            for (int k = 0; k < n; ++k)
                if (stream.pair_index[k] != stream.pair_index.front()) a.c.add(eval::classify(r.masks[k], ref[k]));
            rep.ablation.push_back(a);
        }
        rep.notes.push_back("Ablation rows score every pair but the first (the spec model has no incomplete last pair).");
    }

    // ---- deviations (cycle source) -----------------------------------------------------
    if (source == eval::Source::cycle) {
        std::fprintf(stderr, "eval: deviation catalog...\n");
        const Geometry g{stream.frames[0].width, stream.frames[0].height};
        const int W = g.width, H = g.height;
        const spec::SpecModel sm;
        const auto sp = eval::run_spec(stream, spec::Options{}, o.threads);
        const int x_lost = g.width / 2 - 1, x_lost2 = x_lost + g.dj();          // latched under load
        const int x_hw_max = g.width / 2 - 1 + g.dj(), y_hw_max = g.height / 2 - 1 + g.di();
        long lost_col = 0, outside = 0, drift = 0, residual = 0, diff_total = 0;
        long lost_col_px = 0, outside_px = 0;
        std::vector<std::vector<std::uint8_t>> at_hw_thr(n);
        tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
        arena.execute([&] {
            tbb::parallel_for(0, n, [&](int k) {
                if (!scored(k)) return;
                spec::Response r;
                sm.response(stream.frames[k], r);
                const auto& tm = cyc.thr_map[k];
                sm.corners(r, [&](int x, int y) { return tm[static_cast<size_t>(y) * W + x] < 0 ? INT64_MAX / 4 : tm[static_cast<size_t>(y) * W + x]; },
                           at_hw_thr[k]);
            });
        });
        long scored_frames = 0;
        for (int k = 0; k < n; ++k) {
            if (!scored(k)) continue;
            ++scored_frames;
            const auto& hw = run.masks[k];
            const auto& s = sp.masks[k];
            const auto& t = at_hw_thr[k];
            for (int y = 3; y < H - 3; ++y)
                for (int x = 3; x < W - 3; ++x) {
                    const size_t i = static_cast<size_t>(y) * W + x;
                    const bool in_spec = x <= W - 4 && y <= H - 4;
                    if (!in_spec) continue;
                    const bool out_hw = x > x_hw_max || y > y_hw_max;
                    const bool lost = !out_hw && (x == x_lost || x == x_lost2);
                    if (k == 0) {}
                    diff_total += hw[i] != s[i];
                    if (out_hw) { outside += s[i]; continue; }
                    if (lost) { lost_col += s[i]; continue; }
                    drift += s[i] != t[i];
                    residual += hw[i] != t[i];
                }
        }
        lost_col_px = 2L * (g.height / 2 - 3) * scored_frames;
        outside_px = static_cast<long>((W - 4) - x_hw_max) * (H - 7) + static_cast<long>((H - 4) - y_hw_max) * (W - 7);
        rep.deviations.push_back({"window of a row's last column latched while load is high (never processed)",
                                  fmt::format("columns x = {} and {} (rows 3..{}): {} pixels per frame", x_lost, x_lost2,
                                              y_hw_max, 2 * (g.height / 2 - 3)),
                                  lost_col, "spec corners on those columns, summed over scored frames (the hardware reports none)"});
        rep.deviations.push_back({"find-max period (h/2-3)(w/2+3)*4 != enabled steps per frame: threshold drifts",
                                  fmt::format("every processed pixel; {} maxima published over {} frames", cyc.max_publications, n),
                                  drift, "pixels where spec corners with the previous frame's maximum differ from spec corners with the threshold the cycle model applied to each window"});
        rep.deviations.push_back({"windows mixing two frames at a frame start (load not raised at frame end)",
                                  fmt::format("{} windows entered find-max with columns of two frames", cyc.mixed_windows), 0,
                                  "window provenance tags of the cycle model; their centres have x < 3 and are never read, they only feed find-max"});
        rep.deviations.push_back({"border and last column/row of odd sizes (centres beyond the host's loops)",
                                  fmt::format("x in {}..{} or y in {}..{}: {} pixels per frame", x_hw_max + 1, W - 4,
                                              y_hw_max + 1, H - 4, outside_px),
                                  outside, "spec corners there, summed over scored frames"});
        rep.deviations.push_back({"unexplained (cycle model vs spec model at the cycle model's thresholds)", "processed pixels",
                                  residual, "must be 0: every remaining difference is a bug"});
        rep.notes.push_back(fmt::format("Cycle vs spec corner masks differ on {} pixels of {} scored frames in total "
                                        "(pixels x,y in 3..w-4, 3..h-4).", diff_total, scored_frames));
        rep.notes.push_back(fmt::format("Cycle model: {} writes, {} reads, {:.1f} s.", cyc.writes, cyc.reads, cyc.seconds));
    }

    // ---- outputs -----------------------------------------------------------------------
    for (int f : overlays)
        eval::write_overlay(fs::path(o.out) / fmt::format("overlay_{:03}.png", f), stream.frames[f], run.masks[f], ref[f]);
    rep.seconds_total = secs();
    eval::write_plot(o.out, rep);
    eval::write_reports(o.out, rep);
    std::fprintf(stderr, "eval: %s: recall %.6f precision %.6f (TP %llu FP %llu FN %llu) in %.2f s; report in %s\n",
                 rep.source.c_str(), rep.total.recall(), rep.total.precision(), (unsigned long long)rep.total.tp,
                 (unsigned long long)rep.total.fp, (unsigned long long)rep.total.fn, rep.seconds_total,
                 (fs::path(o.out) / "summary.md").c_str());
}

}  // namespace

void add_eval_command(CLI::App& app) {
    auto o = std::make_shared<EvalOptions>();
    CLI::App* cmd = app.add_subcommand(
        "eval", "precision/recall of the co-processor against OpenCV's Harris (thesis 6.3.2), with ablation");
    cmd->add_option("--kitti", o->kitti, "KITTI odometry root holding sequences/ (default: <data>/kitti)");
    cmd->add_option("--sequence", o->sequence, "KITTI sequence")->capture_default_str();
    cmd->add_option("--source", o->source, "corner source: spec, cycle or rtl")->capture_default_str();
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    cmd->add_option("--frames", o->frames, "stereo pair range a:b (b excluded)");
    cmd->add_option("--overlay", o->overlay, "stream frames to draw, e.g. 2,3");
    cmd->add_option("--threads", o->threads, "worker threads (0: all cores)");
    cmd->add_option("--data", o->data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_flag("!--no-ablation", o->ablation, "skip the ablation table");
    cmd->callback([o] { run_eval(*o); });
}

}  // namespace hc::tools
