// lockstep.cpp: see lockstep.hpp.
#include "cosim/verilator/lockstep.hpp"

#include <chrono>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "model/driver/bus_loop.hpp"
#include "model/harris/harris_top.hpp"

namespace hc::vl {

namespace {
using Clock = std::chrono::steady_clock;
double secs(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

std::string hex(std::uint64_t v) {
    std::ostringstream s;
    s << "0x" << std::hex << v;
    return s.str();
}

// The model's provenance tag for the stage holding a field, or nullptr (control signals,
// max/thr, corner bits: not one window's value).
const WindowTag* tag_of(const std::string& field, const StageTags& t) {
    if (field == "icm") return &t.window;
    if (field == "sxm" || field == "sym") return &t.sobel;
    if (field == "mam" || field == "mbm" || field == "mcm") return &t.m;
    if (field == "bfam" || field == "bfbm" || field == "bfcm") return &t.block;
    if (field == "hrm") return &t.response;
    if (field == "trm" || field == "cornerbit") return &t.thresholded;
    return nullptr;
}
// Pixel offset of element (r, c) from its window's centre: 7x7 window centred on (4,4),
// 5x5 gradient/M elements centred on window pixel (r+1, c+1), 3x3 ones on (r+2, c+2).
int centre_offset(int n, int rc) { return n == 7 ? rc - 4 : n == 5 ? rc - 3 : rc - 2; }

constexpr int kRing = 256;   // writes of position history: far more than the pipeline depth

// One empty FrameStats a frame, named from `names` where it has a name.
std::vector<FrameStats> frame_stats(int count, const std::vector<std::string>& names) {
    std::vector<FrameStats> frames(static_cast<std::size_t>(count));
    for (std::size_t k = 0; k < frames.size(); ++k) {
        frames[k].index = static_cast<int>(k);
        frames[k].source = k < names.size() ? names[k] : "";
    }
    return frames;
}

// A mismatch counted, and kept for the report while fewer than `max_reported` are.
void record(RunResult& res, Mismatch m, int max_reported) {
    ++res.mismatches;
    if (static_cast<int>(res.reported.size()) < max_reported) res.reported.push_back(std::move(m));
}

// A corner read counted in the run's and its frame's figures, decoded, and passed to the
// options' read hooks.
void count_read(RunResult& res, FrameStats& fs, const ReadPos& r, std::uint32_t actual,
                const std::vector<Corner>& corners, const RunOptions& opt) {
    ++res.reads;
    ++fs.reads;
    res.corners += static_cast<long>(corners.size());
    fs.corners += static_cast<long>(corners.size());
    if (opt.on_read) opt.on_read(r, actual);
    if (opt.read_rows) {
        std::ostringstream row;
        row << res.writes << ',' << r.frame << ',' << r.x << ',' << r.y << ',' << actual;
        opt.read_rows->push_back(row.str());
    }
}

// The first element of the observation port that differs from the model's after a write, or
// none: later stages follow from it. Its pixel is the window's, traced back through the ring
// of write positions, or the write's own column for control/max/threshold/corner.
std::optional<Mismatch> first_obs_mismatch(const HarrisTop& model, const Formats& f, const std::vector<ObsField>& layout,
                                           const std::vector<ObsSlot>& slots, const std::vector<std::uint32_t>& words,
                                           const HostDriver& drv, const std::vector<WritePos>& ring, const WritePos& pos,
                                           long write) {
    const FlatObservation flat = flatten(model.observe(), f);
    for (std::size_t k = 0; k < slots.size(); ++k) {
        if (!flat.defined[k]) continue;   // 'U' in the RTL: no value to compare
        const ObsSlot& s = slots[k];
        const std::uint64_t mask = s.width >= 64 ? ~0ULL : (std::uint64_t{1} << s.width) - 1;
        const std::uint64_t want = flat.bits[k] & mask, got = obs_value(words, s);
        if (want == got) continue;
        const ObsField& fld = layout[static_cast<std::size_t>(s.field)];
        Mismatch m;
        m.kind = "obs";
        m.write = write;
        m.signal = fld.name + (fld.elements() > 1 ? "(" + std::to_string(s.row) + "," +
                                                         std::to_string(s.col) + ")"
                                                   : "");
        m.stage = fld.stage;
        m.expected = hex(want);
        m.actual = hex(got);
        const WindowTag* tag = tag_of(fld.name, model.tags());
        if (tag && tag->valid() && write - tag->write < kRing) {
            const WritePos& wp = ring[static_cast<std::size_t>(tag->write % kRing)];
            const Corner c = drv.write_centre(wp, tag->quadrant);
            m.frame = c.frame;
            m.quadrant = tag->quadrant;
            m.x = c.x + centre_offset(fld.cols, s.col);
            m.y = c.y + centre_offset(fld.rows, s.row);
        } else {   // control/max/threshold/corner: the write's own column
            const Corner c = drv.write_centre(pos, 0);
            m.frame = c.frame;
            m.x = c.x;
            m.y = c.y;
        }
        return m;
    }
    return std::nullopt;
}

}  // namespace

std::vector<ObsSlot> obs_slots(const Formats& f, int obs_bits) {
    const auto layout = obs_layout(f);
    if (obs_width(f) != obs_bits)
        throw std::runtime_error("the netlist's obs port is " + std::to_string(obs_bits) +
                                 " bits but obs_layout() describes " + std::to_string(obs_width(f)) +
                                 " (built with OBSERVE = false, or layout and RTL disagree)");
    std::vector<ObsSlot> slots;
    int p = 0;   // VHDL index of the element's MSB; Verilog bit = obs_bits - 1 - p
    for (int k = 0; k < static_cast<int>(layout.size()); ++k)
        for (int r = 1; r <= layout[k].rows; ++r)
            for (int c = 1; c <= layout[k].cols; ++c) {
                slots.push_back({k, r, c, obs_bits - p - layout[k].width, layout[k].width});
                p += layout[k].width;
            }
    return slots;
}

std::uint64_t obs_value(const std::vector<std::uint32_t>& words, const ObsSlot& s) {
    // gather the (at most three) words spanning [lsb, lsb+width) into 96 bits
    const int w0 = s.lsb / 32, sh = s.lsb % 32;
    unsigned __int128 acc = 0;
    for (int k = 2; k >= 0; --k) {
        acc <<= 32;
        if (w0 + k < static_cast<int>(words.size())) acc |= words[static_cast<std::size_t>(w0 + k)];
    }
    const std::uint64_t v = static_cast<std::uint64_t>(acc >> sh);
    return s.width >= 64 ? v : v & ((std::uint64_t{1} << s.width) - 1);
}

std::string Mismatch::describe() const {
    std::ostringstream s;
    s << kind << " mismatch after write " << write << ": frame " << frame << ", pixel x=" << x << " y=" << y;
    if (quadrant >= 0) s << ", quadrant " << quadrant;
    else s << " (the write's column: the register holds no window's value)";
    s << ", signal " << signal << " (" << stage << "): expected " << expected
      << " (model), actual " << actual << " (Verilator)";
    return s.str();
}

Mismatch read_mismatch(const HostDriver& drv, const ReadPos& r, std::uint32_t expected, std::uint32_t actual, long write) {
    const std::uint32_t diff = actual ^ expected;
    Mismatch m;
    m.kind = "read";
    m.write = write;
    int bit = -1;
    for (int b = 3; b >= 0; --b)
        if ((diff >> b) & 1U) {
            bit = b;
            break;
        }
    if (bit >= 0) {
        const Corner c = drv.quadrant_centre(r, 3 - bit);
        m.frame = c.frame;
        m.x = c.x;
        m.y = c.y;
        m.quadrant = 3 - bit;
        m.signal = "corner(" + std::to_string(bit) + ")";
        m.expected = std::to_string((expected >> bit) & 1U);
        m.actual = std::to_string((actual >> bit) & 1U);
    } else {
        m.frame = r.frame;
        m.x = r.x;
        m.y = r.y;
        m.signal = "corner";
        m.expected = hex(expected);
        m.actual = hex(actual);
    }
    m.stage = "corner_shift_register";
    return m;
}

RunResult run_lockstep(const Geometry& g, const Formats& f, VerilatedDesign& dut,
                       const std::vector<const Image*>& frames, const std::vector<std::string>& names,
                       const RunOptions& opt) {
    HostDriver check(g, frames);   // the driver's checks of the frames' sizes
    return run_lockstep(g, f, dut, static_cast<int>(frames.size()),
                        [&](int k) { return std::shared_ptr<const Image>(std::shared_ptr<const Image>{}, frames.at(static_cast<std::size_t>(k))); },
                        names, opt);
}

namespace {

/// The two designs of a lock-step run: each write goes to the cycle model, then to the
/// netlist, each timed; the corner bits read back are the netlist's.
struct LockstepPair {
    HarrisTop& model;
    VerilatedDesign& dut;
    Clock::duration t_model{}, t_dut{};
    void write(std::uint32_t data) {
        const auto t0 = Clock::now();
        model.write(data);
        const auto t1 = Clock::now();
        dut.write(data);
        t_model += t1 - t0;
        t_dut += Clock::now() - t1;
    }
    std::uint32_t corner() {
        const auto t0 = Clock::now();
        const std::uint32_t v = dut.corner();
        t_dut += Clock::now() - t0;
        return v;
    }
};

/// A lock-step run's writes and reads: the per-frame counts (a frame handed to `on_frame`
/// once the next frame's body starts), each read compared with the model's, each write's
/// observed registers when asked; a mismatch stops the run unless `keep_going`.
struct LockstepHooks : BusHooks {
    RunResult& res;
    const HostDriver& drv;
    const HarrisTop& model;
    const Formats& f;
    VerilatedDesign& dut;
    const RunOptions& opt;
    std::vector<ObsField> layout;
    std::vector<ObsSlot> slots;
    std::vector<WritePos> ring;
    Clock::time_point t_frame;
    int open_frame = 0;   // lowest frame whose reads are not all done

    void finish_frames_below(int limit) {
        while (open_frame < limit) {
            const auto now = Clock::now();
            res.frames[static_cast<std::size_t>(open_frame)].seconds = secs(now - t_frame);
            t_frame = now;
            if (opt.on_frame) opt.on_frame(res.frames[static_cast<std::size_t>(open_frame)]);
            ++open_frame;
        }
    }
    bool more() const { return !res.stopped_early; }
    bool before(const BusEvent& ev) {
        // a frame is complete once the next frame's body (not its preload) starts
        if (!ev.pos.tail) finish_frames_below(ev.pos.frame);
        ++res.writes;
        ++res.frames[static_cast<std::size_t>(ev.pos.frame)].writes;
        ring[static_cast<std::size_t>(res.writes % kRing)] = ev.pos;
        return true;
    }
    void read(const BusEvent& ev, std::uint32_t actual, const std::vector<Corner>& corners) {
        const ReadPos& r = *ev.read;
        const std::uint32_t expected = model.corner();
        FrameStats& fs = res.frames[static_cast<std::size_t>(r.frame)];
        count_read(res, fs, r, actual, corners, opt);
        if (actual != expected) {
            ++fs.mismatches;
            ++res.read_mismatches;
            record(res, read_mismatch(drv, r, expected, actual, res.writes), opt.max_reported);
            res.stopped_early = !opt.keep_going;
        }
    }
    void after(const BusEvent& ev) {
        if (res.stopped_early || !opt.compare_obs) return;
        if (std::optional<Mismatch> m = first_obs_mismatch(model, f, layout, slots, dut.obs(), drv, ring, ev.pos, res.writes)) {
            record(res, std::move(*m), opt.max_reported);
            ++res.frames[static_cast<std::size_t>(ev.pos.frame)].mismatches;
            res.stopped_early = !opt.keep_going;
        }
    }
};

}  // namespace

RunResult run_lockstep(const Geometry& g, const Formats& f, VerilatedDesign& dut, int count,
                       const FeedDriver::FrameAt& frame, const std::vector<std::string>& names,
                       const RunOptions& opt) {
    RunResult res;
    FeedDriver feed(g, count, frame);
    HarrisTop model(g, f);
    dut.reset();
    res.frames = frame_stats(count, names);
    const auto t_start = Clock::now();
    LockstepHooks hooks{{}, res, feed.driver(), model, f, dut, opt, obs_layout(f), {}, std::vector<WritePos>(kRing), t_start};
    if (opt.compare_obs) hooks.slots = obs_slots(f, dut.obs_bits());
    LockstepPair pair{model, dut};
    BusLoop loop(feed, pair);
    loop.run(hooks);
    if (!res.stopped_early) hooks.finish_frames_below(count);
    res.seconds = secs(Clock::now() - t_start);
    res.verilator_seconds = secs(pair.t_dut);
    res.model_seconds = secs(pair.t_model);
    return res;
}

}  // namespace hc::vl
