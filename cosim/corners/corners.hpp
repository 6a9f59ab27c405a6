// corners.hpp: the co-processor as a corner source, for every caller that takes its corners
// (eval, the landmark chain): the one table of its sources (the frame-level spec model, the
// cycle model through the host driver, the GHDL-synthesised netlist under Verilator), one
// stream fed frame by frame with the threshold carried from frame to frame, and the
// host-driver loop of the cycle and rtl sources written once (DesignStream).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cosim/verilator/gate.hpp"
#include "cosim/verilator/lockstep.hpp"
#include "cosim/verilator/netlist.hpp"
#include "model/driver/bus_loop.hpp"
#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"
#include "model/image/image.hpp"
#include "model/spec/spec_model.hpp"
#include "model/util/errors.hpp"

namespace hc::corners {

// ---- the table of the co-processor's sources -------------------------------------------

enum class Source { spec, cycle, rtl };

/// One row of source_table(), the one list of the co-processor's corner sources: names,
/// parsing, help texts and what each caller does differently come from its properties.
struct SourceInfo {
    Source id;
    const char* name;    ///< the flag value and the reports' name
    const char* help;    ///< what the help texts say of it after its name
    /// streamed write by write in the host driver's order (the cycle model's timing): a
    /// frame's last windows come back only while the next frame is written
    bool cycle_accurate;
    /// the cycle model's registers are seen on every write (thresholds per window, find-max's
    /// publications: eval's deviation catalog; its checkpoints split a sequence in parts)
    bool observed;
    /// needs GHDL and Verilator: the netlist, trusted once the GHDL/Verilator/model gate passes,
    /// run in lock step with the cycle model (a whole stream at a time)
    bool needs_simulator;
};
/// Every source, in the order of the enum.
const std::vector<SourceInfo>& source_table();
const SourceInfo& source_info(Source s);
/// A table name; InputError "unknown <what> '<name>' (one of: ...)" else (what: the flag, say).
Source parse_source(const std::string& name, const std::string& what = "corner source");
std::string source_name(Source s);
/// The names joined by ", " (with_help: each followed by its help in parentheses).
std::string source_list(bool with_help = false);

// ---- the netlist behind its gate -------------------------------------------------------

/// The netlist of rtl/ for `g` and `f` as source `s` uses it, built (cached) only after the
/// GHDL/Verilator/model gate for `f` passes (cached per design and tools,
/// cosim/verilator/gate.hpp), the logs on `log`. InputError without GHDL and Verilator; a
/// gate that does not pass is its verdict's failure, as `verilate` reports it: a translation
/// fault TranslationFault (status 4), an RTL fault MismatchError (status 1).
std::unique_ptr<vl::VerilatedDesign> trusted_netlist(Source s, const Geometry& g, const Formats& f, std::ostream& log);
/// Nothing for a gate that passed; else its verdict's failure, as trusted_netlist() throws it.
void require_gate_pass(Source s, const vl::GateResult& gate);

// ---- the host-driver loop --------------------------------------------------------------

/// The design a cycle-accurate source writes: the cycle model alone (cycle), or the netlist
/// and the cycle model in lock step (rtl), every read compared: the corner bits handed on
/// are the netlist's, and a read where the two disagree is a MismatchError naming it.
struct Design {
    HarrisTop& model;
    vl::VerilatedDesign* netlist = nullptr;   ///< null: the cycle model alone
    void write(std::uint32_t data) {
        model.write(data);
        if (netlist) netlist->write(data);
    }
    std::uint32_t corner() const { return netlist ? netlist->corner() : model.corner(); }
};

/// A cycle or rtl source over a stream of `frames` frames asked of `frame_at` as the host
/// driver reaches them (FeedDriver: two held at a time), fed to a Design through BusLoop.
/// The caller's hooks (BusHooks) see every write and read: eval records its per-frame
/// register data there, the frame stream its masks. The model and the driver may be restored
/// to a saved state before the first run.
class DesignStream {
public:
    /// `netlist` null: the cycle model alone; else the netlist (reset here) in lock step.
    /// std::invalid_argument as HostDriver for a geometry it refuses.
    DesignStream(const Geometry& g, const Formats& f, int frames, FeedDriver::FrameAt frame_at,
                 vl::VerilatedDesign* netlist = nullptr);
    /// Runs events until a hook stops the loop (true) or the stream ends (false).
    template <class Hooks>
    bool run(Hooks& h) {
        Checked<Hooks> c{{}, h, *this};
        return loop_.run(c);
    }
    HarrisTop& model() { return model_; }
    FeedDriver& feed() { return feed_; }
    const HostDriver& driver() const { return feed_.driver(); }
    vl::VerilatedDesign* netlist() const { return design_.netlist; }
    long writes() const { return model_.writes(); }

private:
    /// MismatchError for a read where the netlist's corner word differs from the model's.
    void check_read(const ReadPos& r, std::uint32_t value) const;
    /// The caller's hooks, each read checked first.
    template <class Hooks>
    struct Checked : BusHooks {
        Hooks& h;
        const DesignStream& s;
        bool more() { return h.more(); }
        bool before(const BusEvent& ev) { return h.before(ev); }
        void read(const BusEvent& ev, std::uint32_t value, const std::vector<Corner>& cs) {
            if (s.design_.netlist) s.check_read(*ev.read, value);
            h.read(ev, value, cs);
        }
        void after(const BusEvent& ev) { h.after(ev); }
    };
    HarrisTop model_;
    FeedDriver feed_;
    Design design_;
    BusLoop<FeedDriver, Design> loop_;
};

// ---- one stream of frames, frame by frame ----------------------------------------------

/// The frame at stream index k, asked in order as the source reaches it (a cycle-accurate
/// source asks for a frame before the previous one's corners are all read).
using FrameAt = std::function<std::shared_ptr<const Image>(int frame)>;

struct StreamRequest {
    Geometry geometry;          ///< every frame's size
    int frames = 0;             ///< frames in the stream
    FrameAt frame_at;
    Formats formats{};          ///< the bit widths (spec: the spec options' formats are these)
    /// spec: the frame before the stream, for its maximum only (the first frame's threshold);
    /// none: the reset value, as the cycle-accurate sources start
    std::shared_ptr<const Image> before;
    int threads = 0;            ///< spec: threads of the responses (0: all cores)
    /// spec: frames run at a time, asked of frame_at ahead of the one handed on (0: twice the
    /// threads, 2 to 16)
    int batch = 0;
    /// a line per frame on stderr as a cycle-accurate source reaches it, led by this (empty: none)
    std::string progress;
};

/// One frame's corners as a stream hands them on.
struct StreamFrame {
    int frame = 0;                    ///< stream index
    std::vector<std::uint8_t> mask;   ///< row-major, 1 = corner
    /// spec: the threshold applied and the frame's own response maximum; -1 where the source
    /// does not observe them (the netlist has no observation port)
    std::int64_t thr = -1, max = -1;
};

/// A source over a stream of frames: each call hands on the next frame's corners, in order,
/// the threshold carried from frame to frame (spec: the spec model one frame at a time with
/// the previous frame's maximum, a batch of frames ahead at a time with their responses in
/// parallel; cycle and rtl: one DesignStream, a frame complete once the next frame's body
/// starts or the stream ends). Memory does not grow with the stream.
class CornerStream {
public:
    virtual ~CornerStream() = default;
    /// The next frame's corners; false after the last frame.
    virtual bool next(StreamFrame& out) = 0;
};

/// InputError naming the formats' first refused field.
void check_formats(const Formats& f);

/// The stream of source `s`; a source that needs the simulator gets its trusted_netlist()
/// here, whose failures it throws. InputError: formats it refuses; std::invalid_argument: a
/// geometry the host driver refuses.
std::unique_ptr<CornerStream> open_stream(Source s, StreamRequest r);

}  // namespace hc::corners
