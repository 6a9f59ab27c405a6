// evaluate.cpp: the whole evaluation of `harris-cosim eval` (evaluate.hpp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "cosim/verilator/gate.hpp"
#include "cosim/verilator/lockstep.hpp"
#include "cosim/verilator/netlist.hpp"
#include "eval/evaluate.hpp"
#include "model/driver/host_driver.hpp"

namespace fs = std::filesystem;

namespace hc::eval {

// The default stream of a machine without KITTI: pairs of consecutive frames of OpenCV's
// sample video vtest.avi (opencv-doc), grey, centred 640x360 crop (the thesis's camera
// size); without opencv-doc, the synthetic `blocks` pattern.
Stream default_stream(int first, int last) {
    Stream s;
    const std::string video = HC_OPENCV_SAMPLE_VIDEO;
    const int pairs = std::min(last, 12) - first;
    if (pairs <= 0) throw InputError("--frames selects no pair of the default 12-pair stream");
    cv::VideoCapture cap;
    if (!video.empty() && fs::exists(video) && cap.open(video)) {
        cv::Mat f, g;
        for (int k = 0; k < 2 * std::min(last, 12) && cap.read(f); ++k) {
            if (k < 2 * first) continue;
            cv::cvtColor(f, g, cv::COLOR_BGR2GRAY);
            Image im(g.cols, g.rows);
            for (int r = 0; r < g.rows; ++r) std::copy_n(g.ptr<std::uint8_t>(r), g.cols, &im.at(r, 0));
            s.frames.push_back(frames::crop(im, 640, 360, video));
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

namespace {

/// The RTL as a corner source: the GHDL-synthesised netlist under Verilator (trusted only
/// after its GHDL/Verilator/model gate passes), streamed exactly like the cycle model; the
/// masks come from the corner bits the netlist returns on every read. `mismatches` counts
/// reads where the netlist and the cycle model (run in lock step) disagree.
SourceRun run_rtl_source(const Stream& stream, long& mismatches) {
    const auto t0 = std::chrono::steady_clock::now();
    const Formats f{};
    const fs::path cache = vl::default_cache_dir();
    bool cached = false;
    const vl::GateResult gate = vl::run_gate_cached(f, {}, cache, std::cerr, &cached);
    if (gate.verdict != vl::GateVerdict::pass)
        throw MismatchError("--source rtl: the GHDL/Verilator/model gate did not pass (" +
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
    SourceRun run;
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
            throw InternalError("--source rtl: unreadable read row '" + row + "'");
        cs.clear();
        drv.decode(ReadPos{frame, x, y}, value, cs);
        for (const Corner& c : cs) run.masks[static_cast<size_t>(c.frame)][static_cast<size_t>(c.y) * g.width + c.x] = 1;
    }
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return run;
}

}  // namespace

Report evaluate(const Request& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    const Source source = o.source;
    if (source == Source::rtl) {
        std::string why;
        if (!vl::toolchain_available(&why)) throw InputError("--source rtl needs GHDL and Verilator: " + why);
    }
    const int first = o.pairs.first, last = o.pairs.last;
    const std::vector<int>& overlays = o.overlays;
    cv::setNumThreads(1);   // frames run in parallel; OpenCV's own threads would oversubscribe

    // ---- frames ------------------------------------------------------------------------
    std::fprintf(stderr, "eval: loading frames...\n");
    Stream stream;
    const fs::path& kitti_dir = o.kitti;
    if (!kitti_dir.empty())
        stream = frames::load_kitti_stream(kitti_dir, o.sequence, o.pairs, o.pairs_flag, o.threads, 2);
    else
        stream = default_stream(first, last);
    const int n = static_cast<int>(stream.frames.size());
    for (int f : overlays)
        if (f < 0 || f >= n) throw InputError(fmt::format("--overlay frame {} is not in the stream (0..{})", f, n - 1));
    fs::create_directories(o.out);
    std::fprintf(stderr, "eval: %s\n", stream.description.c_str());

    // ---- reference ---------------------------------------------------------------------
    std::fprintf(stderr, "eval: OpenCV reference on %d frames...\n", n);
    const double tr0 = secs();
    const auto ref = run_reference(stream, spec::ReferenceOptions{}, o.threads);
    const double t_ref = secs() - tr0;

    // ---- source ------------------------------------------------------------------------
    std::fprintf(stderr, "eval: %s source...\n", source_name(source).c_str());
    SourceRun run;
    CycleRun cyc;
    long rtl_mismatches = 0;
    if (source == Source::spec) {
        run = run_spec(stream, spec::Options{}, o.threads);
    } else if (source == Source::rtl) {
        run = run_rtl_source(stream, rtl_mismatches);
    } else {
        cyc = run_cycle(stream, Formats{}, true);
        run = cyc;
    }
    // scoring: drop the first pair (threshold seed) and, for the cycle model, the last
    // (its last windows are read only while a next pair is written)
    const int last_pair = stream.pair_index.back();
    auto scored = [&](int k) {
        return stream.pair_index[k] != stream.pair_index.front() &&
               (source == Source::spec || stream.pair_index[k] != last_pair);
    };
    Report rep;
    rep.source = source_name(source);
    rep.stream = stream.description;
    rep.threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
    rep.command = o.command;
    rep.seconds_source = run.seconds;
    if (source == Source::rtl)
        rep.notes.push_back(fmt::format(
            "RTL source: GHDL-synthesised netlist under Verilator (gate passed), {} reads disagreeing with the "
            "cycle model run in lock step; the thr/max columns are not observed on the netlist (-1).",
            rtl_mismatches));
    rep.seconds_reference = t_ref;
    for (int k = 0; k < n; ++k) {
        FrameRow row;
        row.frame = k;
        row.name = stream.names[k];
        row.pair = stream.pair_index[k];
        row.scored = scored(k);
        row.c = classify(run.masks[k], ref[k]);
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
            const auto r = run_spec(stream, v.opt, o.threads);
            AblationRow a{v.name, v.opt.describe(), {}};
            for (int k = 0; k < n; ++k)
                if (stream.pair_index[k] != stream.pair_index.front()) a.c.add(classify(r.masks[k], ref[k]));
            rep.ablation.push_back(a);
        }
        rep.notes.push_back("Ablation rows score every pair but the first (the spec model has no incomplete last pair).");
    }

    // ---- deviations (cycle source) -----------------------------------------------------
    if (source == Source::cycle) {
        std::fprintf(stderr, "eval: deviation catalog...\n");
        const Geometry g{stream.frames[0].width, stream.frames[0].height};
        const int W = g.width, H = g.height;
        const spec::SpecModel sm;
        const auto sp = run_spec(stream, spec::Options{}, o.threads);
        const int x_lost = g.width / 2 - 1, x_lost2 = x_lost + g.dj();          // latched under load
        const int x_hw_max = g.width / 2 - 1 + g.dj(), y_hw_max = g.height / 2 - 1 + g.di();
        long lost_col = 0, outside = 0, drift = 0, residual = 0, diff_total = 0;
        long outside_px = 0;
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
                    diff_total += hw[i] != s[i];
                    if (out_hw) { outside += s[i]; continue; }
                    if (lost) { lost_col += s[i]; continue; }
                    drift += s[i] != t[i];
                    residual += hw[i] != t[i];
                }
        }
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
    for (int f : overlays) {
        const std::string file = fmt::format("overlay_{:03}.png", f);
        write_overlay(fs::path(o.out) / file, stream.frames[f], run.masks[f], ref[f]);
        rep.overlays.push_back(file);
    }
    rep.seconds_total = secs();
    write_plot(o.out, rep);
    write_reports(o.out, rep);
    return rep;
}

}  // namespace hc::eval
