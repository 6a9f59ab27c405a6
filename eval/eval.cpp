// eval.cpp: see eval.hpp.
#include "eval/eval.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "model/harris/harris_top.hpp"

namespace hc::eval {

Confusion classify(const std::vector<std::uint8_t>& test, const std::vector<std::uint8_t>& ref) {
    if (test.size() != ref.size()) throw std::invalid_argument("classify: masks of different sizes");
    std::uint64_t both = 0, t = 0, r = 0;
    for (size_t i = 0; i < test.size(); ++i) {   // vectorises: three popcount-like sums
        both += test[i] & ref[i];
        t += test[i];
        r += ref[i];
    }
    Confusion c;
    c.tp = both;
    c.fp = t - both;
    c.fn = r - both;
    c.tn = test.size() - c.tp - c.fp - c.fn;
    return c;
}

Source parse_source(const std::string& s) {
    if (s == "spec") return Source::spec;
    if (s == "cycle") return Source::cycle;
    if (s == "rtl") return Source::rtl;
    throw InputError("unknown --source '" + s + "' (spec, cycle or rtl)");
}

std::string source_name(Source s) {
    switch (s) {
    case Source::spec: return "spec";
    case Source::cycle: return "cycle";
    case Source::rtl: return "rtl";
    }
    return "?";
}

namespace {
double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

SourceRun run_spec(const Stream& s, const spec::Options& o, int threads) {
    const auto t0 = std::chrono::steady_clock::now();
    const spec::SpecModel m(o);
    std::vector<const Image*> ptrs;
    for (const auto& f : s.frames) ptrs.push_back(&f);
    std::int64_t prev = m.reset_max();
    auto fc = m.run(ptrs, prev, threads);
    SourceRun r;
    for (auto& f : fc) {
        r.masks.push_back(std::move(f.mask));
        r.thr.push_back(f.thr);
        r.max.push_back(f.max);
    }
    r.seconds = since(t0);
    return r;
}

CycleRun run_cycle(const Stream& s, const Formats& f, bool progress) {
    const auto t0 = std::chrono::steady_clock::now();
    const Geometry g{s.frames.at(0).width, s.frames.at(0).height};
    std::vector<const Image*> ptrs;
    for (const auto& fr : s.frames) ptrs.push_back(&fr);
    HostDriver drv(g, ptrs);
    HarrisTop top(g, f);
    const size_t npix = static_cast<size_t>(g.width) * g.height;
    const int n = static_cast<int>(s.frames.size());
    CycleRun r;
    r.masks.assign(n, std::vector<std::uint8_t>(npix, 0));
    r.thr_map.assign(n, std::vector<std::int64_t>(npix, -1));
    r.thr.assign(n, 0);
    r.max.assign(n, 0);
    r.publications_in_frame.assign(n, 0);
    std::vector<WritePos> pos;   // WritePos of every write, index = write number - 1
    pos.reserve(static_cast<size_t>(drv.total_writes()));
    std::vector<bool> thr_seen(n, false);
    std::vector<Corner> corners;
    BusEvent ev;
    long last_report = 0;
    while (drv.next(ev)) {
        pos.push_back(ev.pos);
        const Word thr_before = top.thr();
        const long count_before = top.find_max().count;
        // a window whose response enters find-max on this write, mixing two frames: its
        // newest column is one of a frame's first 6 columns of its first row (the 6 older
        // columns of the 7x7 window come from the previous frame's last row)
        if (top.t() & (1U << 4)) {
            const WindowTag w = top.tags().response;
            if (w.valid()) {
                const WritePos& p = pos[static_cast<size_t>(w.write - 1)];
                if (p.frame > 0 && p.i == 3 && p.j < 6) ++r.mixed_windows;
            }
        }
        top.write(ev.data);
        const int fr = ev.pos.frame;
        // a publication: the period counter wrapped to 1 on this write
        if (top.find_max().count == 1 && count_before != 1) {
            ++r.max_publications;
            ++r.publications_in_frame[fr];
            r.max[fr] = top.find_max().max.value();
        }
        // the window thresholded on this write: remember its threshold by image position
        const WindowTag th = top.tags().thresholded;
        if (th.valid()) {
            const Corner c = drv.write_centre(pos[static_cast<size_t>(th.write - 1)], th.quadrant);
            if (c.x >= 0 && c.y >= 0 && c.x < g.width && c.y < g.height) {
                r.thr_map[c.frame][static_cast<size_t>(c.y) * g.width + c.x] = thr_before.value();
                if (!thr_seen[c.frame]) {
                    thr_seen[c.frame] = true;
                    r.thr[c.frame] = thr_before.value();
                }
            }
        }
        if (ev.read) {
            ++r.reads;
            corners.clear();
            drv.decode(*ev.read, top.corner(), corners);
            for (const Corner& c : corners) r.masks[c.frame][static_cast<size_t>(c.y) * g.width + c.x] = 1;
        }
        if (progress && top.writes() - last_report >= 2'000'000) {
            last_report = top.writes();
            std::fprintf(stderr, "\r  cycle model: frame %d/%d, %.0f%% of writes, %.0f s", fr + 1, n,
                         100.0 * top.writes() / drv.total_writes(), since(t0));
        }
    }
    if (progress) std::fprintf(stderr, "\n");
    r.writes = top.writes();
    r.seconds = since(t0);
    return r;
}

std::vector<std::vector<std::uint8_t>> run_reference(const Stream& s, const spec::ReferenceOptions& o,
                                                     int threads, std::vector<double>* max) {
    const int n = static_cast<int>(s.frames.size());
    std::vector<std::vector<std::uint8_t>> masks(n);
    std::vector<double> mx(n);
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(0, n, [&](int k) { mx[k] = spec::opencv_corners(s.frames[k], o, masks[k]); });
    });
    if (max) *max = mx;
    return masks;
}

}  // namespace hc::eval
