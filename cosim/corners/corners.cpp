// corners.cpp: see corners.hpp.
#include "cosim/corners/corners.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <stdexcept>

#include <tbb/task_arena.h>

#include "model/util/table.hpp"

namespace hc::corners {

const std::vector<SourceInfo>& source_table() {
    static const std::vector<SourceInfo> table{
        {Source::spec, "spec", "the co-processor's frame-level spec model", false, false, false},
        {Source::cycle, "cycle", "its cycle model", true, true, false},
        {Source::rtl, "rtl", "its netlist under Verilator", true, false, true},
    };
    return table;
}

const SourceInfo& source_info(Source s) { return util::row_of(source_table(), s, "a corner source"); }

Source parse_source(const std::string& name, const std::string& what) { return util::row_named(source_table(), name, what); }

std::string source_name(Source s) { return source_info(s).name; }

std::string source_list(bool with_help) { return util::row_names(source_table(), with_help); }

std::unique_ptr<vl::VerilatedDesign> trusted_netlist(Source s, const Geometry& g, const Formats& f, std::ostream& log) {
    std::string why;
    if (!vl::toolchain_available(&why)) throw InputError("corner source " + source_name(s) + " needs GHDL and Verilator: " + why);
    require_gate_pass(s, vl::run_gate_cached(f, {}, vl::default_cache_dir(), log, nullptr));
    const vl::NetlistConfig nc{g, f, false, {}};
    return std::make_unique<vl::VerilatedDesign>(vl::build_netlist(nc, vl::default_cache_dir(), log), vl::config_key(nc));
}

void require_gate_pass(Source s, const vl::GateResult& gate) {
    if (gate.verdict == vl::GateVerdict::pass) return;
    const std::string failed = "corner source " + source_name(s) + ": the GHDL/Verilator/model gate did not pass (" +
                               vl::verdict_name(gate.verdict) + "): " + gate.first;
    switch (gate.verdict) {
        case vl::GateVerdict::pass: break;
        case vl::GateVerdict::translation_fault: throw TranslationFault(failed);
        case vl::GateVerdict::rtl_fault: throw MismatchError(failed);
    }
    throw InternalError(failed);
}

DesignStream::DesignStream(const Geometry& g, const Formats& f, int frames, FeedDriver::FrameAt frame_at,
                           vl::VerilatedDesign* netlist)
    : model_(g, f), feed_(g, frames, std::move(frame_at)), design_{model_, netlist}, loop_(feed_, design_) {
    if (netlist) netlist->reset();
}

void DesignStream::check_read(const ReadPos& r, std::uint32_t value) const {
    const std::uint32_t expected = model_.corner();
    if (value != expected)
        throw MismatchError("rtl: the netlist and the cycle model run in lock step disagree: " +
                            vl::read_mismatch(driver(), r, expected, value, model_.writes()).describe());
}

namespace {

/// The spec model over the stream, the previous frame's maximum carried: a batch of frames
/// at a time (their responses in parallel), handed on one by one.
class SpecFrames : public CornerStream {
public:
    explicit SpecFrames(StreamRequest r)
        : r_(std::move(r)), spec_(options(r_.formats), r_.before.get()),
          arena_(r_.threads > 0 ? r_.threads : tbb::task_arena::automatic) {}
    bool next(StreamFrame& out) override {
        if (done_ == ahead_.size()) fill();
        if (done_ == ahead_.size()) return false;
        spec::FrameCorners& fc = ahead_[done_++];
        out.frame = k_++;
        out.mask = std::move(fc.mask);
        out.thr = fc.thr;
        out.max = fc.max;
        return true;
    }

private:
    static spec::Options options(const Formats& f) {
        spec::Options o;
        o.formats = f;
        return o;
    }
    /// The next batch of frames (StreamRequest::batch).
    void fill() {
        const int batch = r_.batch > 0 ? r_.batch : std::clamp(2 * arena_.max_concurrency(), 2, 16);
        const int first = k_, last = std::min(r_.frames, k_ + batch);
        std::vector<std::shared_ptr<const Image>> held;
        std::vector<const Image*> ptrs;
        for (int k = first; k < last; ++k) {
            held.push_back(r_.frame_at(k));
            ptrs.push_back(held.back().get());
        }
        ahead_ = ptrs.empty() ? std::vector<spec::FrameCorners>{} : spec_.run(ptrs, arena_);
        done_ = 0;
    }
    StreamRequest r_;
    spec::SpecStream spec_;
    tbb::task_arena arena_;
    std::vector<spec::FrameCorners> ahead_;   // the batch in hand
    std::size_t done_ = 0;                    // of it handed on
    int k_ = 0;
};

/// The cycle model, or the netlist in lock step with it, through one DesignStream: the
/// corners read back into their frames' masks; a frame is handed on once the next frame's
/// body (not its preload) starts, or the stream ends.
class DesignFrames : public CornerStream {
public:
    /// `netlist` null: the cycle model alone.
    DesignFrames(Source s, StreamRequest r, std::unique_ptr<vl::VerilatedDesign> netlist)
        : s_(s), r_(std::move(r)), netlist_(std::move(netlist)),
          design_(r_.geometry, r_.formats, r_.frames, r_.frame_at, netlist_.get()) {}
    bool next(StreamFrame& out) override {
        if (k_ >= r_.frames) return false;
        if (!ended_) {
            Hooks h{{}, *this, k_};
            ended_ = !design_.run(h);
        }
        out.frame = k_;
        const auto it = masks_.find(k_);
        if (it == masks_.end()) out.mask.assign(npix(), 0);
        else {
            out.mask = std::move(it->second);
            masks_.erase(it);
        }
        ++k_;
        return true;
    }

private:
    std::size_t npix() const {
        return static_cast<std::size_t>(r_.geometry.width) * static_cast<std::size_t>(r_.geometry.height);
    }
    /// Stops before the first write of a frame body after `last`; the corners into masks.
    struct Hooks : BusHooks {
        DesignFrames& s;
        int last;
        bool before(const BusEvent& ev) const { return ev.pos.tail || ev.pos.frame <= last; }
        void after(const BusEvent& ev) {
            if (s.r_.progress.empty() || ev.pos.frame == s.progress_frame_) return;
            s.progress_frame_ = ev.pos.frame;
            std::fprintf(stderr, "%s: %s frame %d/%d, %.0f s\n", s.r_.progress.c_str(), source_name(s.s_).c_str(),
                         ev.pos.frame + 1, s.r_.frames,
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - s.t0_).count());
        }
        void read(const BusEvent&, std::uint32_t, const std::vector<Corner>& cs) {
            const std::size_t w = static_cast<std::size_t>(s.r_.geometry.width);
            for (const Corner& c : cs) {
                if (c.frame < s.k_)
                    throw InternalError("corner source " + source_name(s.s_) + ": a corner of frame " +
                                        std::to_string(c.frame) + " read after the frame was handed on");
                auto& m = s.masks_[c.frame];
                if (m.empty()) m.assign(s.npix(), 0);
                m[static_cast<std::size_t>(c.y) * w + static_cast<std::size_t>(c.x)] = 1;
            }
        }
    };
    Source s_;
    StreamRequest r_;
    std::unique_ptr<vl::VerilatedDesign> netlist_;
    DesignStream design_;
    std::map<int, std::vector<std::uint8_t>> masks_;   // frame -> corners read so far
    int k_ = 0;
    bool ended_ = false;
    int progress_frame_ = -1;
    std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

}  // namespace

void check_formats(const Formats& f) {
    try {
        f.validate();
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string("formats: ") + e.what());
    }
}

std::unique_ptr<CornerStream> open_stream(Source s, StreamRequest r) {
    check_formats(r.formats);
    const SourceInfo& info = source_info(s);
    if (!info.cycle_accurate) return std::make_unique<SpecFrames>(std::move(r));
    std::unique_ptr<vl::VerilatedDesign> net;
    if (info.needs_simulator) net = trusted_netlist(s, r.geometry, r.formats, std::cerr);
    return std::make_unique<DesignFrames>(s, std::move(r), std::move(net));
}

}  // namespace hc::corners
