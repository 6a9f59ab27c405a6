// eval.cpp: see eval.hpp.
#include "eval/eval.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <optional>
#include <cstdio>
#include <stdexcept>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "model/driver/bus_loop.hpp"
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

namespace {
double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

SourceRun run_spec(const Stream& s, const spec::Options& o, int threads, const Image* before) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<const Image*> ptrs;
    for (const auto& f : s.frames) ptrs.push_back(&f);
    auto fc = spec::SpecStream(o, before).run(ptrs, threads);
    SourceRun r;
    for (auto& f : fc) {
        r.masks.push_back(std::move(f.mask));
        r.thr.push_back(f.thr);
        r.max.push_back(f.max);
    }
    r.seconds = since(t0);
    return r;
}

namespace {

/// How many of the last writes' positions a checkpoint keeps: more than any stage tag lags
/// behind the write it is seen on (a run from a checkpoint throws if one ever does).
constexpr std::size_t kRecentWrites = 256;

/// The host driver over a span's frames: the stream's frames at their place in the whole
/// stream, a blank frame for the others (never sent: the span starts and stops inside it).
struct SpanDriver {
    Image blank;
    HostDriver drv;
    SpanDriver(const Stream& s, int offset, int frames_total)
        : blank(s.frames.at(0).width, s.frames.at(0).height),
          drv(Geometry{blank.width, blank.height}, pointers(s, offset, frames_total, blank)) {}
    static std::vector<const Image*> pointers(const Stream& s, int offset, int frames_total, const Image& blank) {
        if (offset < 0 || offset + static_cast<int>(s.frames.size()) > frames_total)
            throw InternalError("cycle span: frames [" + std::to_string(offset) + ", " +
                                std::to_string(offset + s.frames.size()) + ") outside a stream of " +
                                std::to_string(frames_total));
        std::vector<const Image*> p(static_cast<std::size_t>(frames_total), &blank);
        for (std::size_t k = 0; k < s.frames.size(); ++k) p[static_cast<std::size_t>(offset) + k] = &s.frames[k];
        return p;
    }
};

template <class Driver>   // HostDriver or FeedDriver
void start_at(const CycleCheckpoint* c, HarrisTop& top, Driver& drv) {
    if (!c) return;
    try {
        top.restore_state(c->model);
        drv.restore(c->driver);
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string("cycle model checkpoint does not fit this stream: ") + e.what());
    }
}

/// The positions of the last kRecentWrites writes: write number w at ring[w % size], from
/// a checkpoint's recent writes when a run starts from one.
class WriteRing {
public:
    WriteRing(long begin, const CycleCheckpoint* start) : ring_(kRecentWrites), oldest_(begin + 1), newest_(begin) {
        if (!start) return;
        const auto& rec = start->recent;
        oldest_ = begin + 1 - static_cast<long>(rec.size());
        for (std::size_t i = 0; i < rec.size(); ++i) ring_[static_cast<std::size_t>(oldest_ + static_cast<long>(i)) & (kRing - 1)] = rec[i];
    }
    /// Write number `write` (the newest) went to `pos`.
    void push(long write, const WritePos& pos) {
        newest_ = write;
        ring_[static_cast<std::size_t>(write) & (kRing - 1)] = pos;
    }
    const WritePos& pos_of(long write) const {
        if (write < oldest_ || write <= newest_ - kRing || write > newest_)
            throw InternalError("cycle span: a stage holds write " + std::to_string(write) +
                                ", older than the recent writes kept");
        return ring_[static_cast<std::size_t>(write) & (kRing - 1)];
    }
    /// The positions a checkpoint after write `last` keeps, oldest first.
    std::vector<WritePos> recent(long last) const {
        std::vector<WritePos> r;
        for (long k = std::max(oldest_, last - kRing + 1); k <= last; ++k) r.push_back(ring_[static_cast<std::size_t>(k) & (kRing - 1)]);
        return r;
    }

private:
    static constexpr long kRing = static_cast<long>(kRecentWrites);
    static_assert((kRecentWrites & (kRecentWrites - 1)) == 0, "the ring indexes by a mask");
    std::vector<WritePos> ring_;
    long oldest_;   // the oldest write whose position the ring holds
    long newest_;   // the newest write in the ring
};

/// The frames of a span still open, from `first()` on; a frame is handed on once the driver
/// writes the body of the frame two after it (no stage lags by a frame).
class OpenFrames {
public:
    OpenFrames(const CycleSpan& span, std::size_t npix) : span_(span), npix_(npix), first_(span.first) {}
    /// The open frame `frame` (opened with the ones before it when new); `what` names the
    /// event in the error when the frame is complete already or outside the span.
    CycleFrame& slot(int frame, const char* what) {
        if (frame < first_ || frame >= span_.last)
            throw InternalError(std::string("cycle span: ") + what + " of frame " + std::to_string(frame) +
                                (frame < first_ ? " after the frame was complete" : " outside the span's frames [" +
                                 std::to_string(span_.first) + ", " + std::to_string(span_.last) + ")"));
        while (first_ + static_cast<int>(open_.size()) <= frame) {
            CycleFrame c;
            c.frame = first_ + static_cast<int>(open_.size());
            c.mask.assign(npix_, 0);
            c.thr_index.assign(npix_, 0);
            open_.push_back(std::move(c));
            thr_seen_.push_back(false);
        }
        return open_[static_cast<std::size_t>(frame - first_)];
    }
    /// Every open frame below `frame` (and inside the span) handed to `on_frame`.
    void hand_on_below(int frame, const std::function<void(CycleFrame&&)>& on_frame) {
        while (first_ < std::min(frame, span_.last)) {
            slot(first_, "the end");
            on_frame(std::move(open_.front()));
            open_.pop_front();
            thr_seen_.erase(thr_seen_.begin());
            ++first_;
        }
    }
    /// A find-max publication on a write of frame `fr`: the frame's, or the next frame's
    /// (its preloaded columns) when `fr` is the span's end.
    void publication(CycleCounts& r, int fr, std::int64_t max) {
        ++r.max_publications;
        if (fr == span_.last) {
            ++r.next_publications;
            r.next_max = max;
        } else {
            CycleFrame& c = slot(fr, "a publication");
            ++c.publications;
            c.max = max;
        }
    }
    /// The window centred on `c` thresholded with `v`: its threshold remembered by image
    /// position, and the frame's first threshold as the frame's.
    void threshold(const Corner& c, int width, std::int64_t v) {
        CycleFrame& s = slot(c.frame, "a thresholded window");
        std::size_t idx = 0;
        while (idx < s.thr_values.size() && s.thr_values[idx] != v) ++idx;
        if (idx == s.thr_values.size()) {
            if (idx == 255) throw InternalError("cycle run: more than 255 thresholds in frame " + std::to_string(c.frame));
            s.thr_values.push_back(v);
        }
        s.thr_index[static_cast<size_t>(c.y) * width + c.x] = static_cast<std::uint8_t>(idx + 1);
        const std::size_t k = static_cast<std::size_t>(c.frame - first_);
        if (!thr_seen_[k]) {
            thr_seen_[k] = true;
            s.thr = v;
        }
    }

private:
    const CycleSpan& span_;
    std::size_t npix_;
    std::deque<CycleFrame> open_;
    int first_;
    std::vector<bool> thr_seen_;
};

}  // namespace

CycleRun run_cycle(const Stream& s, const Formats& f, bool progress) {
    const int n = static_cast<int>(s.frames.size());
    return run_cycle(s, f, CycleSpan{0, 0, n, n, nullptr, 0}, progress);
}

CycleRun run_cycle(const Stream& s, const Formats& f, const CycleSpan& span, bool progress) {
    const Geometry g{s.frames.at(0).width, s.frames.at(0).height};
    const int held = static_cast<int>(s.frames.size());
    if (span.offset < 0 || span.offset + held > span.frames_total)
        throw InternalError("cycle span: frames [" + std::to_string(span.offset) + ", " +
                            std::to_string(span.offset + held) + ") outside a stream of " +
                            std::to_string(span.frames_total));
    const FrameAt at = [&](int k) -> std::shared_ptr<const Image> {
        const int i = k - span.offset;
        if (i < 0 || i >= held)
            throw InternalError("cycle span: frame " + std::to_string(k) + " is not among the frames held");
        return {std::shared_ptr<const Image>{}, &s.frames[static_cast<std::size_t>(i)]};   // not owned
    };
    CycleRun r;
    const CycleCounts c = run_cycle(at, g, f, span, progress, [&](CycleFrame&& fr) {
        std::vector<std::int64_t> tm(fr.thr_index.size());
        for (std::size_t i = 0; i < tm.size(); ++i) tm[i] = fr.thr_at(i);
        r.masks.push_back(std::move(fr.mask));
        r.thr_map.push_back(std::move(tm));
        r.thr.push_back(fr.thr);
        r.max.push_back(fr.max);
        r.publications_in_frame.push_back(fr.publications);
    });
    r.writes = c.writes;
    r.reads = c.reads;
    r.mixed_windows = c.mixed_windows;
    r.max_publications = c.max_publications;
    r.next_publications = c.next_publications;
    r.next_max = c.next_max;
    r.seconds = c.seconds;
    return r;
}

std::string chain_digest(const CycleCheckpoint& c) { return util::hex64(util::fnv1a(to_json(c).dump())); }

namespace {

/// The digest of the state a span with an end write leaves for the next part (empty
/// without one); InternalError when the stream ended before that write.
std::string end_digest(const CycleSpan& span, const HarrisTop& top, const HostDriver& drv, const WriteRing& ring) {
    if (!span.end_write) return "";
    if (top.writes() != span.end_write)
        throw InternalError("cycle span: the stream ended after " + std::to_string(top.writes()) + " writes, before " +
                            std::to_string(span.end_write));
    CycleCheckpoint c;
    c.frame = span.last;
    c.model = top.save_state();
    c.driver = drv.state();
    c.writes = top.writes();
    c.recent = ring.recent(top.writes());
    return chain_digest(c);
}

/// What a cycle run does on each write and read of its span: the positions of the recent
/// writes, the frames handed on, the windows mixing two frames, find-max's publications,
/// each thresholded window's threshold, the corners read back, the progress line.
struct CycleHooks : BusHooks {
    const CycleSpan& span;
    const Geometry& g;
    const HarrisTop& top;
    const HostDriver& drv;
    WriteRing& ring;
    OpenFrames& open;
    CycleCounts& r;
    const std::function<void(CycleFrame&&)>& on_frame;
    bool progress;
    std::chrono::steady_clock::time_point t0;
    // the threshold the design applies (it follows find-max's published maximum) and the
    // period counter, as they were before the write in hand
    std::int64_t thr_now;
    long count_before;
    std::int64_t thr_before = 0;
    long last_report = 0;
    int body_frame = -1;
    bool more() const { return span.end_write == 0 || top.writes() < span.end_write; }
    bool before(const BusEvent& ev) {
        ring.push(top.writes() + 1, ev.pos);   // this write's number
        const int fr = ev.pos.frame;
        if (!ev.pos.tail && fr != body_frame) {   // a frame's body starts
            body_frame = fr;
            open.hand_on_below(fr - 1, on_frame);
        }
        thr_before = thr_now;
        // a window whose response enters find-max on this write, mixing two frames: its
        // newest column is one of a frame's first 6 columns of its first row (the 6 older
        // columns of the 7x7 window come from the previous frame's last row)
        if (top.t() & (1U << 4)) {
            const WindowTag wt = top.tags().response;
            if (wt.valid()) {
                const WritePos& p = ring.pos_of(wt.write);
                if (p.frame > 0 && p.i == 3 && p.j < 6) ++r.mixed_windows;
            }
        }
        return true;
    }
    void after(const BusEvent& ev) {
        // a publication: the period counter wrapped to 1 on this write
        const long count = top.find_max_count();
        const bool published = count == 1 && count_before != 1;
        count_before = count;
        if (count == 1) thr_now = top.thr().value();   // the maximum changes only where the counter is 1
        if (published) open.publication(r, ev.pos.frame, top.find_max().max.value());
        // the window thresholded on this write: remember its threshold by image position
        const WindowTag th = top.tags().thresholded;
        if (th.valid()) {
            const Corner c = drv.write_centre(ring.pos_of(th.write), th.quadrant);
            if (c.x >= 0 && c.y >= 0 && c.x < g.width && c.y < g.height)
                open.threshold(c, g.width, thr_before);
        }
        if (progress && top.writes() - last_report >= 2'000'000) {
            last_report = top.writes();
            std::fprintf(stderr, "\r  cycle model: frame %d/%d, %.0f%% of writes, %.0f s", ev.pos.frame + 1,
                         span.frames_total, 100.0 * top.writes() / drv.total_writes(), since(t0));
        }
    }
    void read(const BusEvent&, std::uint32_t, const std::vector<Corner>& corners) {
        ++r.reads;
        for (const Corner& c : corners) open.slot(c.frame, "a corner").mask[static_cast<size_t>(c.y) * g.width + c.x] = 1;
    }
};

}  // namespace

CycleCounts run_cycle(const FrameAt& frames, const Geometry& g, const Formats& f, const CycleSpan& span, bool progress,
                      const std::function<void(CycleFrame&&)>& on_frame) {
    const auto t0 = std::chrono::steady_clock::now();
    if (span.first < 0 || span.first >= span.last || span.last > span.frames_total)
        throw InternalError("cycle span: frames [" + std::to_string(span.first) + ", " + std::to_string(span.last) +
                            ") of a stream of " + std::to_string(span.frames_total));
    corners::DesignStream design(g, f, span.frames_total, frames);
    const HostDriver& drv = design.driver();
    HarrisTop& top = design.model();
    start_at(span.start, top, design.feed());
    const size_t npix = static_cast<size_t>(g.width) * g.height;
    CycleCounts r;
    const long begin = span.start ? span.start->writes : 0;
    WriteRing ring(begin, span.start);
    OpenFrames open(span, npix);
    CycleHooks hooks{{}, span, g, top, drv, ring, open, r, on_frame, progress, t0, top.thr().value(), top.find_max_count()};
    design.run(hooks);
    if (progress) std::fprintf(stderr, "\n");
    r.end_digest = end_digest(span, top, drv, ring);
    open.hand_on_below(span.last, on_frame);
    r.writes = top.writes() - begin;
    r.seconds = since(t0);
    return r;
}

namespace {

/// A run up to a frame's body: the checkpoint there, the recent writes' positions and, after
/// `margin` writes, find-max's publications.
struct CheckpointHooks : BusHooks {
    const HostDriver& drv;
    const HarrisTop& top;
    std::deque<WritePos>& recent;
    int to;
    long begin, margin;
    long* publications;
    DriverState state_before{};
    long count_before = 0;
    std::optional<CycleCheckpoint> at;
    bool more() {
        state_before = drv.state();
        return true;
    }
    bool before(const BusEvent& ev) {
        if (ev.pos.frame == to && !ev.pos.tail) {
            CycleCheckpoint c;
            c.frame = to;
            c.model = top.save_state();
            c.driver = state_before;
            c.writes = top.writes();
            c.recent.assign(recent.begin(), recent.end());
            at = std::move(c);
            return false;
        }
        count_before = top.find_max().count;
        return true;
    }
    void after(const BusEvent& ev) {
        if (publications && top.writes() - begin > margin && top.find_max().count == 1 && count_before != 1)
            ++*publications;
        recent.push_back(ev.pos);
        if (recent.size() > kRecentWrites) recent.pop_front();
    }
};

/// The model from `from` (rebased to `rebase` = {writes, count} when given) up to frame
/// `to`'s body; counts find-max publications after the first `margin` writes.
CycleCheckpoint run_to(const Stream& s, const Formats& f, int offset, int frames_total, const CycleCheckpoint* from,
                       const long* rebase, int to, long margin = 0, long* publications = nullptr) {
    const Geometry g{s.frames.at(0).width, s.frames.at(0).height};
    if (to <= (from ? from->driver.frame : 0) || to >= frames_total || to >= offset + static_cast<int>(s.frames.size()))
        throw InternalError("cycle checkpoint: frame " + std::to_string(to) + " is not after the start and in the stream");
    SpanDriver sd(s, offset, frames_total);
    HostDriver& drv = sd.drv;
    HarrisTop top(g, f);
    start_at(from, top, drv);
    if (rebase) top.rebase(rebase[0], rebase[1]);
    const long begin = top.writes();
    std::deque<WritePos> recent;
    if (from) recent.assign(from->recent.begin(), from->recent.end());
    CheckpointHooks hooks{{}, drv, top, recent, to, begin, margin, publications};
    BusLoop loop(drv, top);
    loop.run(hooks);
    if (!hooks.at) throw InternalError("cycle checkpoint: the stream ended before frame " + std::to_string(to));
    return std::move(*hooks.at);
}

HarrisTop model_of(const CycleCheckpoint& c, const Geometry& g, const Formats& f) {
    HarrisTop top(g, f);
    top.restore_state(c.model);
    return top;
}

}  // namespace

CycleCheckpoint cycle_checkpoint(const Stream& s, const Formats& f, int offset, int frames_total,
                                 const CycleCheckpoint* from, int to) {
    return run_to(s, f, offset, frames_total, from, nullptr, to);
}

CheckpointBase checkpoint_base(const Stream& s, const Formats& f, int frames_total) {
    const Geometry g{s.frames.at(0).width, s.frames.at(0).height};
    CheckpointBase b;
    b.at1 = cycle_checkpoint(s, f, 0, frames_total, nullptr, 1);
    const CycleCheckpoint at2 = cycle_checkpoint(s, f, 0, frames_total, &b.at1, 2);
    b.period = g.find_max_period();
    b.writes_per_frame = at2.writes - b.at1.writes;
    const long c1 = model_of(b.at1, g, f).find_max().count, c2 = model_of(at2, g, f).find_max().count;
    b.count_per_frame = ((c2 - c1) % b.period + b.period) % b.period;
    return b;
}

CycleCheckpoint warm_checkpoint(const Stream& s, const Formats& f, int offset, int frames_total,
                                const CheckpointBase& base, int to, int warm, int min_publications) {
    const Geometry g{s.frames.at(0).width, s.frames.at(0).height};
    const int from = to - warm;
    if (from < 1) throw InternalError("warm checkpoint: the warm-up would start before frame 1");
    CycleCheckpoint start = base.at1;
    start.frame = from;
    start.driver.frame = from;
    for (WritePos& p : start.recent) p.frame += from - 1;
    const long c1 = model_of(base.at1, g, f).find_max().count;
    const long rebase[2] = {base.at1.writes + (from - 1) * base.writes_per_frame,
                            (c1 - 1 + (from - 1) * base.count_per_frame) % base.period + 1};
    start.writes = rebase[0];
    long publications = 0;
    // the pipeline holds no window older than a few columns: publications after the first
    // kRecentWrites writes see only responses of the warm-up's own pixels
    CycleCheckpoint c = run_to(s, f, offset, frames_total, &start, rebase, to, static_cast<long>(kRecentWrites),
                               &publications);
    if (publications < min_publications)
        throw InternalError("warm checkpoint: " + std::to_string(publications) + " find-max publication(s) in a warm-up of " +
                            std::to_string(warm) + " frames; at least " + std::to_string(min_publications) +
                            " are needed to flush the maximum");
    return c;
}

namespace {

std::string hex_of(const std::string& bytes) {
    static const char* d = "0123456789abcdef";
    std::string h;
    h.reserve(bytes.size() * 2);
    for (unsigned char c : bytes) {
        h += d[c >> 4];
        h += d[c & 15];
    }
    return h;
}

std::string bytes_of(const std::string& hex) {
    if (hex.size() % 2) throw InputError("cycle model checkpoint: odd number of hex digits");
    const auto nib = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        throw InputError(std::string("cycle model checkpoint: '") + c + "' is not a hex digit");
    };
    std::string b(hex.size() / 2, '\0');
    for (std::size_t i = 0; i < b.size(); ++i) b[i] = static_cast<char>(nib(hex[2 * i]) << 4 | nib(hex[2 * i + 1]));
    return b;
}

}  // namespace

nlohmann::json to_json(const CycleCheckpoint& c) {
    const DriverState& d = c.driver;
    nlohmann::json recent = nlohmann::json::array();
    for (const WritePos& p : c.recent) recent.push_back({p.frame, p.i, p.j, p.k, p.tail});
    return {{"frame", c.frame},
            {"writes", c.writes},
            {"model", hex_of(c.model)},
            {"driver", {d.frame, d.i, d.j, d.k, d.in_tail, d.tail_col, d.preload, d.done, d.px[0], d.px[1], d.px[2],
                        d.py[0], d.py[1], d.py[2], d.column_open}},
            {"recent", recent}};
}

CycleCheckpoint checkpoint_from_json(const nlohmann::json& j) {
    try {
        CycleCheckpoint c;
        c.frame = j.at("frame").get<int>();
        c.writes = j.at("writes").get<long>();
        c.model = bytes_of(j.at("model").get<std::string>());
        const auto& d = j.at("driver");
        if (d.size() != 15) throw InputError("cycle model checkpoint: the driver state has " + std::to_string(d.size()) + " fields, not 15");
        DriverState& s = c.driver;
        s.frame = d[0]; s.i = d[1]; s.j = d[2]; s.k = d[3]; s.in_tail = d[4]; s.tail_col = d[5];
        s.preload = d[6]; s.done = d[7];
        for (int n = 0; n < 3; ++n) {
            s.px[n] = d[8 + n];
            s.py[n] = d[11 + n];
        }
        s.column_open = d[14];
        for (const auto& p : j.at("recent")) c.recent.push_back(WritePos{p.at(0), p.at(1), p.at(2), p.at(3), p.at(4)});
        return c;
    } catch (const nlohmann::json::exception& e) {
        throw InputError(std::string("cycle model checkpoint: ") + e.what());
    }
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
