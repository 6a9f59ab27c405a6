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
#include "eval/sequences.hpp"
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

std::vector<AblationVariant> ablation_variants() {
    std::vector<AblationVariant> vs;
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
    return vs;
}

namespace {

/// Frames [a, b) of a stream (indices into it).
Stream slice(const Stream& s, int a, int b) {
    Stream o;
    o.frames.assign(s.frames.begin() + a, s.frames.begin() + b);
    o.names.assign(s.names.begin() + a, s.names.begin() + b);
    o.pair_index.assign(s.pair_index.begin() + a, s.pair_index.begin() + b);
    o.description = s.description;
    return o;
}

}  // namespace

Part evaluate_part(const PartInput& in) {
    const Stream& s = *in.stream;
    const int held = static_cast<int>(s.frames.size());
    const bool look_back = in.first > 0;   // the previous frame's maximum sets the first threshold
    if (in.first >= in.last || in.first - (look_back ? 1 : 0) < in.offset || in.last > in.offset + held ||
        in.last > in.frames_total)
        throw InternalError(fmt::format("eval part: frames [{}, {}) and their neighbours are not in the frames [{}, {}) held",
                                        in.first, in.last, in.offset, in.offset + held));
    const Source source = in.source;
    const Stream own = slice(s, in.first - in.offset, in.last - in.offset);
    const int n = in.last - in.first;
    // the spec model over the part, its first threshold from the previous frame's maximum:
    // that frame's response only, not its corners
    const auto spec_run = [&](const spec::Options& opt) {
        return run_spec(own, opt, in.threads, look_back ? &s.frames[in.first - in.offset - 1] : nullptr);
    };
    Part p;
    p.sequence = own.names.front().substr(0, own.names.front().find('/'));
    p.width = own.frames[0].width;
    p.height = own.frames[0].height;
    p.first_pair = in.first_pair;
    p.last_pair = in.last_pair;

    const auto t0 = std::chrono::steady_clock::now();
    const auto ref = run_reference(own, spec::ReferenceOptions{}, in.threads);
    p.seconds_reference = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    SourceRun run;
    CycleRun cyc;
    if (source == Source::spec) {
        run = spec_run(spec::Options{});
    } else if (source == Source::rtl) {
        if (in.first != 0 || in.last != in.frames_total)
            throw InternalError("eval part: the RTL source runs whole sequences only");
        run = run_rtl_source(own, p.rtl_mismatches);
    } else {
        cyc = run_cycle(s, Formats{}, CycleSpan{in.offset, in.first, in.last, in.frames_total, in.start, in.end_write},
                        true);
        run = cyc;
        p.publications = cyc.publications_in_frame;
        p.next_publications = cyc.next_publications;
        p.next_max = cyc.next_max;
        p.mixed_windows = cyc.mixed_windows;
        p.max_publications = cyc.max_publications;
        p.writes = cyc.writes;
        p.reads = cyc.reads;
    }
    p.seconds_source = run.seconds;
    // scoring: drop the first pair (threshold seed) and, but for the spec model, the last
    // (its last windows are read only while a next pair is written)
    auto scored = [&](int k) {
        return own.pair_index[k] != in.first_pair && (source == Source::spec || own.pair_index[k] != in.last_pair);
    };
    for (int k = 0; k < n; ++k) {
        FrameRow row;
        row.frame = in.first + k;
        row.name = own.names[k];
        row.pair = own.pair_index[k];
        row.scored = scored(k);
        row.c = classify(run.masks[k], ref[k]);
        row.source_corners = spec::count_corners(run.masks[k]);
        row.reference_corners = spec::count_corners(ref[k]);
        row.thr = run.thr[k];
        row.max = run.max[k];
        p.rows.push_back(row);
        if (in.on_masks) in.on_masks(in.first + k, own.frames[k], run.masks[k], ref[k]);
    }

    if (in.ablation) {
        for (const auto& v : ablation_variants()) {
            const auto r = spec_run(v.opt);
            Confusion c;
            for (int k = 0; k < n; ++k)
                if (own.pair_index[k] != in.first_pair) c.add(classify(r.masks[k], ref[k]));
            p.ablation.push_back(c);
        }
    }

    // ---- deviations (cycle source) -----------------------------------------------------
    if (source == Source::cycle) {
        const Geometry g{p.width, p.height};
        const int W = g.width, H = g.height;
        const spec::SpecModel sm;
        const auto sp = spec_run(spec::Options{});
        const int x_lost = g.width / 2 - 1, x_lost2 = x_lost + g.dj();          // latched under load
        const int x_hw_max = g.width / 2 - 1 + g.dj(), y_hw_max = g.height / 2 - 1 + g.di();
        std::vector<std::vector<std::uint8_t>> at_hw_thr(n);
        tbb::task_arena arena(in.threads > 0 ? in.threads : tbb::task_arena::automatic);
        arena.execute([&] {
            tbb::parallel_for(0, n, [&](int k) {
                if (!scored(k)) return;
                spec::Response r;
                sm.response(own.frames[k], r);
                const auto& tm = cyc.thr_map[k];
                sm.corners(r, [&](int x, int y) { return tm[static_cast<size_t>(y) * W + x] < 0 ? INT64_MAX / 4 : tm[static_cast<size_t>(y) * W + x]; },
                           at_hw_thr[k]);
            });
        });
        for (int k = 0; k < n; ++k) {
            if (!scored(k)) continue;
            ++p.scored_frames;
            const auto& hw = run.masks[k];
            const auto& sk = sp.masks[k];
            const auto& t = at_hw_thr[k];
            for (int y = 3; y < H - 3; ++y)
                for (int x = 3; x < W - 3; ++x) {
                    const size_t i = static_cast<size_t>(y) * W + x;
                    const bool in_spec = x <= W - 4 && y <= H - 4;
                    if (!in_spec) continue;
                    const bool out_hw = x > x_hw_max || y > y_hw_max;
                    const bool lost = !out_hw && (x == x_lost || x == x_lost2);
                    p.diff_total += hw[i] != sk[i];
                    if (out_hw) { p.outside += sk[i]; continue; }
                    if (lost) { p.lost_col += sk[i]; continue; }
                    p.drift += sk[i] != t[i];
                    p.residual += hw[i] != t[i];
                }
        }
    }
    return p;
}

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
    std::fprintf(stderr, "eval: OpenCV reference, %s source%s on %d frames...\n", source_name(source).c_str(),
                 o.ablation ? ", ablation" : "", n);

    PartInput in;
    in.source = source;
    in.stream = &stream;
    in.first = 0;
    in.last = n;
    in.frames_total = n;
    in.first_pair = stream.pair_index.front();
    in.last_pair = stream.pair_index.back();
    in.ablation = o.ablation;
    in.threads = o.threads;
    std::vector<std::string> overlay_files;
    in.on_masks = [&](int k, const Image& img, const std::vector<std::uint8_t>& src, const std::vector<std::uint8_t>& ref) {
        if (std::find(overlays.begin(), overlays.end(), k) == overlays.end()) return;
        const std::string file = fmt::format("overlay_{:03}.png", k);
        write_overlay(fs::path(o.out) / file, img, src, ref);
        overlay_files.push_back(file);
    };
    const Part part = evaluate_part(in);

    Report rep = merge_parts({part}, source, o.ablation);
    rep.stream = stream.description;
    rep.threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
    rep.command = o.command;
    rep.seconds_source = part.seconds_source;
    rep.seconds_reference = part.seconds_reference;
    for (int f : overlays)   // in the order asked for
        if (std::find(overlay_files.begin(), overlay_files.end(), fmt::format("overlay_{:03}.png", f)) != overlay_files.end())
            rep.overlays.push_back(fmt::format("overlay_{:03}.png", f));
    rep.seconds_total = secs();
    write_plot(o.out, rep);
    write_reports(o.out, rep);
    return rep;
}

}  // namespace hc::eval
