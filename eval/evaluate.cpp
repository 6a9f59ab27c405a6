// evaluate.cpp: the whole evaluation of `harris-cosim eval` (evaluate.hpp).
#include <algorithm>
#include <chrono>
#include <deque>
#include <cstdio>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>
#include <iostream>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "cosim/corners/corners.hpp"
#include "eval/evaluate.hpp"
#include "eval/sequences.hpp"
#include "model/driver/host_driver.hpp"

namespace fs = std::filesystem;

namespace hc::eval {

namespace {

/// A reported frame's source output, as a source hands it on.
struct SourceFrame {
    std::vector<std::uint8_t> mask;
    std::int64_t thr = -1, max = -1;
    CycleFrame cycle;   ///< the cycle source's thresholds per window (else empty)
};

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

/// The scoring of a part a batch of frames at a time, in frame order: the reference, the
/// spec model (the spec source, the ablation, the deviations), the rows and the counts.
/// Holds only the batch's frames and masks, and one maximum per spec model run.
class PartScorer {
public:
    PartScorer(const PartInput& in, Part& p) : in_(in), p_(p), feed_(*in.feed), arena_(in.threads > 0 ? in.threads : tbb::task_arena::automatic) {
        std::shared_ptr<const Image> before;
        if (in.first > 0) before = feed_.frame(in.first - 1 - in.offset);
        const spec::Options thesis{};
        spec_.emplace_back(thesis, before.get());
        if (in.ablation)
            for (const auto& v : ablation_variants()) {
                // a variant with the thesis's options is the thesis run itself
                variant_run_.push_back(v.opt.describe() == thesis.describe() ? 0 : spec_.size());
                if (variant_run_.back() != 0) spec_.emplace_back(v.opt, before.get());
                p.ablation.emplace_back();
            }
    }
    /// Frames the scorer takes at a time.
    int batch() const { return std::clamp(2 * arena_.max_concurrency(), 2, 16); }

    /// Scores frames [a, b) (stream indices), whose source output `src` holds.
    void score(int a, int b, const std::vector<SourceFrame>& src) {
        const int n = b - a;
        const corners::SourceInfo& source = corners::source_info(in_.source);
        std::vector<std::shared_ptr<const Image>> imgs(static_cast<std::size_t>(n));
        std::vector<const Image*> ptrs(static_cast<std::size_t>(n));
        std::vector<std::vector<std::uint8_t>> ref(static_cast<std::size_t>(n));
        const auto t0 = std::chrono::steady_clock::now();
        arena_.execute([&] {
            tbb::parallel_for(0, n, [&](int k) {
                imgs[k] = feed_.frame(a + k - in_.offset);
                ptrs[k] = imgs[k].get();
                spec::opencv_corners(*imgs[k], spec::ReferenceOptions{}, ref[k]);
            });
        });
        p_.seconds_reference += since(t0);
        std::vector<std::vector<spec::FrameCorners>> runs(spec_.size());
        // the thesis's spec run: the observed source's deviations, the ablation; a source that
        // is not cycle-accurate is that run (the spec model at the thesis's formats), taken
        // from its frames rather than run twice
        if (source.observed || in_.ablation) runs[0] = source.cycle_accurate ? spec_[0].run(ptrs, arena_) : as_spec_run(src);
        for (std::size_t v = 1; v < spec_.size(); ++v) runs[v] = spec_[v].run(ptrs, arena_);

        const auto pair_of = [&](int k) { return feed_.pair_index()[static_cast<std::size_t>(a + k - in_.offset)]; };
        // scoring: drop the first pair (threshold seed) and, for a cycle-accurate source, the
        // last (its last windows are read only while a next pair is written)
        const auto scored = [&](int k) {
            return pair_of(k) != in_.first_pair && (!source.cycle_accurate || pair_of(k) != in_.last_pair);
        };
        const auto mask_of = [&](int k) -> const std::vector<std::uint8_t>& { return src[static_cast<std::size_t>(k)].mask; };
        for (int k = 0; k < n; ++k) {
            FrameRow row;
            row.frame = a + k;
            row.name = feed_.names()[static_cast<std::size_t>(a + k - in_.offset)];
            row.pair = pair_of(k);
            row.scored = scored(k);
            row.c = classify(mask_of(k), ref[k]);
            row.source_corners = spec::count_corners(mask_of(k));
            row.reference_corners = spec::count_corners(ref[k]);
            row.thr = src[k].thr;
            row.max = src[k].max;
            p_.rows.push_back(row);
            if (in_.on_masks) in_.on_masks(a + k, *imgs[k], mask_of(k), ref[k]);
        }
        for (std::size_t v = 0; v < variant_run_.size(); ++v)
            for (int k = 0; k < n; ++k)
                if (pair_of(k) != in_.first_pair) p_.ablation[v].add(classify(runs[variant_run_[v]][k].mask, ref[k]));
        if (source.observed) deviations(n, imgs, src, runs[0], scored);
    }

private:
    static std::vector<spec::FrameCorners> as_spec_run(const std::vector<SourceFrame>& src) {
        std::vector<spec::FrameCorners> run(src.size());
        for (std::size_t k = 0; k < src.size(); ++k) {
            run[k].mask = src[k].mask;
            run[k].thr = src[k].thr;
            run[k].max = src[k].max;
            run[k].count = spec::count_corners(src[k].mask);
        }
        return run;
    }
    template <class Scored>
    void deviations(int n, const std::vector<std::shared_ptr<const Image>>& imgs, const std::vector<SourceFrame>& src,
                    const std::vector<spec::FrameCorners>& sp, const Scored& scored) {
        const Geometry g{p_.width, p_.height};
        const int W = g.width, H = g.height;
        const spec::SpecModel& sm = spec_[0].model();
        const int x_lost = g.width / 2 - 1, x_lost2 = x_lost + g.dj();          // latched under load
        const int x_hw_max = g.width / 2 - 1 + g.dj(), y_hw_max = g.height / 2 - 1 + g.di();
        std::vector<std::vector<std::uint8_t>> at_hw_thr(static_cast<std::size_t>(n));
        arena_.execute([&] {
            tbb::parallel_for(0, n, [&](int k) {
                if (!scored(k)) return;
                spec::Response r;
                sm.response(*imgs[k], r);
                const CycleFrame& c = src[k].cycle;
                sm.corners(r, [&](int x, int y) {
                    const std::int64_t t = c.thr_at(static_cast<size_t>(y) * W + x);
                    return t < 0 ? INT64_MAX / 4 : t;
                }, at_hw_thr[k]);
            });
        });
        for (int k = 0; k < n; ++k) {
            if (!scored(k)) continue;
            ++p_.scored_frames;
            const auto& hw = src[k].mask;
            const auto& sk = sp[k].mask;
            const auto& t = at_hw_thr[k];
            for (int y = 3; y < H - 3; ++y)
                for (int x = 3; x < W - 3; ++x) {
                    const size_t i = static_cast<size_t>(y) * W + x;
                    const bool in_spec = x <= W - 4 && y <= H - 4;
                    if (!in_spec) continue;
                    const bool out_hw = x > x_hw_max || y > y_hw_max;
                    const bool lost = !out_hw && (x == x_lost || x == x_lost2);
                    p_.diff_total += hw[i] != sk[i];
                    if (out_hw) { p_.outside += sk[i]; continue; }
                    if (lost) { p_.lost_col += sk[i]; continue; }
                    p_.drift += sk[i] != t[i];
                    p_.residual += hw[i] != t[i];
                }
        }
    }
    static double since(std::chrono::steady_clock::time_point t0) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    const PartInput& in_;
    Part& p_;
    frames::FrameFeed& feed_;
    tbb::task_arena arena_;
    std::vector<spec::SpecStream> spec_;          ///< [0]: the thesis's options, then the variants'
    std::vector<std::size_t> variant_run_;  ///< per ablation variant, its run in spec_
};

/// One job at a time on a thread of its own, kept for the whole part (a thread started per
/// job leaves allocator state behind for each, which grows with the stream).
class Background {
public:
    Background() : t_([this] { loop(); }) {}
    ~Background() {
        {
            const std::lock_guard<std::mutex> lock(m_);
            stop_ = true;
        }
        cv_.notify_all();
        t_.join();
    }
    /// Waits for the job before (rethrowing what it threw), then starts `job`.
    void run(std::function<void()> job) {
        wait();
        {
            const std::lock_guard<std::mutex> lock(m_);
            job_ = std::move(job);
        }
        cv_.notify_all();
    }
    /// Waits for the running job; rethrows what it threw.
    void wait() {
        std::unique_lock<std::mutex> lock(m_);
        cv_.wait(lock, [&] { return !job_; });
        if (err_) std::rethrow_exception(std::exchange(err_, nullptr));
    }

private:
    void loop() {
        std::unique_lock<std::mutex> lock(m_);
        for (;;) {
            cv_.wait(lock, [&] { return stop_ || job_; });
            if (!job_) return;
            lock.unlock();
            std::exception_ptr e;
            try {
                job_();
            } catch (...) {
                e = std::current_exception();
            }
            lock.lock();
            err_ = e;
            job_ = nullptr;
            cv_.notify_all();
        }
    }
    std::mutex m_;
    std::condition_variable cv_;
    std::function<void()> job_;
    std::exception_ptr err_;
    bool stop_ = false;
    std::thread t_;
};

/// The cycle source of a part: the model streams the part's frames (decoded ahead) and
/// hands them to the scorer `batch` at a time, scored on a second thread while the model
/// runs on when there are two; the counts and digests go into `p`.
void run_cycle_source(const PartInput& in, frames::FrameFeed& feed, PartScorer& scorer, int batch, Part& p) {
    const bool overlap = tbb::this_task_arena::max_concurrency() > 1 && in.threads != 1;
    std::vector<SourceFrame> pending;
    int pending_first = in.first;
    std::optional<Background> scoring;   // scores a batch while the model runs on
    if (overlap) scoring.emplace();
    const auto submit = [&] {
        if (pending.empty()) return;
        const int a = pending_first, size = static_cast<int>(pending.size());
        auto job = [&scorer, &feed, off = in.offset, a, size, fs = std::make_shared<std::vector<SourceFrame>>(std::move(pending))] {
            scorer.score(a, a + size, *fs);
            feed.release_below(a + size - off);
        };
        pending_first += size;
        pending = {};
        if (scoring) scoring->run(std::move(job));
        else job();
    };
    const FrameAt at = [&](int k) {
        auto im = feed.frame(k - in.offset);
        feed.prefetch(k + 1 - in.offset);   // decoded while the model runs
        return im;
    };
    const CycleCounts c = run_cycle(at, Geometry{p.width, p.height}, Formats{},
                                    CycleSpan{in.offset, in.first, in.last, in.frames_total, in.start, in.end_write},
                                    true, [&](CycleFrame&& fr) {
                                        SourceFrame sf;
                                        sf.mask = std::move(fr.mask);
                                        sf.thr = fr.thr;
                                        sf.max = fr.max;
                                        p.publications.push_back(fr.publications);
                                        sf.cycle = std::move(fr);
                                        pending.push_back(std::move(sf));
                                        if (static_cast<int>(pending.size()) == batch) submit();
                                    });
    submit();
    if (scoring) scoring->wait();
    p.next_publications = c.next_publications;
    p.next_max = c.next_max;
    p.mixed_windows = c.mixed_windows;
    p.max_publications = c.max_publications;
    p.writes = c.writes;
    p.reads = c.reads;
    p.seconds_source = c.seconds;
    p.start_digest = in.start ? chain_digest(*in.start) : "";
    p.end_digest = c.end_digest;
}

/// A source behind corners::CornerStream (the spec model; the netlist in lock step with the
/// cycle model, trusted only after its GHDL/Verilator/model gate passes: corners::trusted_netlist):
/// the part's frames streamed (each loaded as the stream reaches it) and handed to the scorer
/// `batch` at a time. The source's time: the netlist's preparation and the stream's own (not
/// the scoring).
void run_stream_source(const PartInput& in, frames::FrameFeed& feed, PartScorer& scorer, int batch, Part& p) {
    const auto t0 = std::chrono::steady_clock::now();
    corners::StreamRequest r;
    r.geometry = Geometry{feed.width(), feed.height()};
    r.formats = Formats{};
    r.frames = in.last - in.first;
    r.threads = in.threads;
    const int off = in.first - in.offset;   // stream frame 0 in the feed
    r.frame_at = [&feed, off](int k) {
        auto im = feed.frame(off + k);
        feed.prefetch(off + k + 1);   // decoded while the source runs
        return im;
    };
    if (in.first > 0) r.before = feed.frame(off - 1);   // its maximum sets the first threshold
    if (corners::source_info(in.source).needs_simulator) {
        if (in.first != 0 || in.last != in.frames_total || in.offset != 0)
            throw InternalError("eval part: the " + source_name(in.source) + " source runs whole sequences only");
        r.progress = "eval";
    }
    const std::unique_ptr<corners::CornerStream> stream = corners::open_stream(in.source, std::move(r));
    const auto since = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    double seconds = since(t0);
    for (int a = in.first; a < in.last; a += batch) {
        const int b = std::min(in.last, a + batch);
        std::vector<SourceFrame> fs(static_cast<std::size_t>(b - a));
        const auto t1 = std::chrono::steady_clock::now();
        for (SourceFrame& sf : fs) {
            corners::StreamFrame fr;
            if (!stream->next(fr)) throw InternalError("eval part: the corner stream ended before frame " + std::to_string(b));
            sf.mask = std::move(fr.mask);
            sf.thr = fr.thr;
            sf.max = fr.max;
        }
        seconds += since(t1);
        scorer.score(a, b, fs);
        feed.release_below(b - in.offset);
    }
    p.seconds_source = seconds;
}

}  // namespace

Part evaluate_part(const PartInput& in) {
    frames::FrameFeed& feed = *in.feed;
    const int held = feed.size();
    const bool look_back = in.first > 0;   // the previous frame's maximum sets the first threshold
    if (in.first >= in.last || in.first - (look_back ? 1 : 0) < in.offset || in.last > in.offset + held ||
        in.last > in.frames_total)
        throw InternalError(fmt::format("eval part: frames [{}, {}) and their neighbours are not in the frames [{}, {}) held",
                                        in.first, in.last, in.offset, in.offset + held));
    const corners::SourceInfo& source = corners::source_info(in.source);
    Part p;
    const std::string& first_name = feed.names()[static_cast<std::size_t>(in.first - in.offset)];
    p.sequence = first_name.substr(0, first_name.find('/'));
    p.width = feed.width();
    p.height = feed.height();
    p.first_pair = in.first_pair;
    p.last_pair = in.last_pair;
    PartScorer scorer(in, p);
    const int batch = scorer.batch();

    if (source.observed) run_cycle_source(in, feed, scorer, batch, p);   // its registers recorded on every write
    else run_stream_source(in, feed, scorer, batch, p);
    return p;
}

Report evaluate(const Request& o) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    const Source source = o.source;
    if (corners::source_info(source).needs_simulator) {
        std::string why;
        if (!vl::toolchain_available(&why))
            throw InputError("--source " + source_name(source) + " needs GHDL and Verilator: " + why);
    }
    const std::vector<int>& overlays = o.overlays;
    cv::setNumThreads(1);   // frames run in parallel; OpenCV's own threads would oversubscribe

    std::fprintf(stderr, "eval: opening the frames...\n");
    frames::FrameFeed feed = frames::open_feed(o.frames, frames::WhenNone::stereo, 2);
    const int n = feed.size();
    for (int f : overlays)
        if (f < 0 || f >= n) throw InputError(fmt::format("--overlay frame {} is not in the stream (0..{})", f, n - 1));
    fs::create_directories(o.out);
    std::fprintf(stderr, "eval: %s\n", feed.description().c_str());
    std::fprintf(stderr, "eval: OpenCV reference, %s source%s on %d frames...\n", source_name(source).c_str(),
                 o.ablation ? ", ablation" : "", n);

    PartInput in;
    in.source = source;
    in.feed = &feed;
    in.first = 0;
    in.last = n;
    in.frames_total = n;
    in.first_pair = feed.pair_index().front();
    in.last_pair = feed.pair_index().back();
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
    rep.stream = feed.description();
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
