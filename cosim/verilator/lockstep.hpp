// lockstep.hpp: a verilated harris_top and the cycle model driven write by write from the
// same host-driver stream, compared on every read and (optionally) every observed register.
//
// Purpose: the checking core of `harris-cosim verilate`. A read compares the 4 corner bits
// the host reads; the observation comparison walks obs_layout() over the obs port after
// every write. A mismatch is located as the thesis's host would see it: frame, image pixel
// of the window (from the model's stage provenance tags), quadrant, signal.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "model/driver/host_driver.hpp"
#include "model/harris/harris_pkg.hpp"
#include "model/harris/observation.hpp"
#include "cosim/verilator/netlist.hpp"

namespace hc::vl {

/// Where the obs port's elements sit: one entry per element of obs_layout() order.
struct ObsSlot {
    int field;      ///< index into obs_layout()
    int row, col;   ///< 1-based element position (1,1 for a scalar)
    int lsb;        ///< Verilog bit index of the element's LSB
    int width;
};
std::vector<ObsSlot> obs_slots(const Formats& f, int obs_bits);
/// Element value of a slot from the obs words (Verilog bit b = words[b/32] bit b%32).
std::uint64_t obs_value(const std::vector<std::uint32_t>& words, const ObsSlot& s);

struct Mismatch {
    std::string kind;       ///< "read" (corner bits) or "obs" (an inter-stage register)
    long write = 0;         ///< 1-based index of the write after which it was seen
    int frame = -1;         ///< frame of the window's pixel
    int x = -1, y = -1;     ///< image pixel (column, row) the value belongs to
    int quadrant = -1;
    std::string signal;     ///< e.g. "corner(3)", "mbm(2,4)"
    std::string stage;      ///< entity driving it
    std::string expected;   ///< model
    std::string actual;     ///< Verilator
    std::string describe() const;
};

/// The mismatch of a corner read after write number `write`: the first differing corner bit
/// (bit 3 = quadrant 0) at its window's pixel; other bits of the word (31..4 must be 0) are
/// reported as the whole word.
Mismatch read_mismatch(const HostDriver& drv, const ReadPos& r, std::uint32_t expected, std::uint32_t actual, long write);

struct FrameStats {
    int index = 0;
    std::string source;
    long writes = 0, reads = 0, corners = 0, mismatches = 0;
    double seconds = 0;   ///< wall time from the frame's first write to its last read
};

struct RunOptions {
    bool compare_obs = false;
    bool keep_going = false;      ///< else stop at the first mismatch
    int max_reported = 20;        ///< mismatches kept in the result
    std::function<void(const FrameStats&)> on_frame;   ///< progress, once per finished frame
    /// when set, every read: write,frame,x,y,value (as `harris-cosim rtl --reads`)
    std::vector<std::string>* read_rows = nullptr;
    /// when set, called on every read with the netlist's corner word (before on_frame of
    /// the read's frame)
    std::function<void(const ReadPos& r, std::uint32_t value)> on_read;
};

struct RunResult {
    std::vector<FrameStats> frames;
    long writes = 0, reads = 0, corners = 0;
    long mismatches = 0;        ///< mismatching reads + writes with a mismatching obs element
    long read_mismatches = 0;   ///< reads whose corner word differs
    std::vector<Mismatch> reported;
    bool stopped_early = false;
    double seconds = 0;            ///< wall time of the whole run
    double verilator_seconds = 0;  ///< time inside the verilated design (write + read)
    double model_seconds = 0;      ///< time inside the cycle model
};

/// Streams `frames` (all of g's size) through `dut` (reset first) and a fresh HarrisTop.
RunResult run_lockstep(const Geometry& g, const Formats& f, VerilatedDesign& dut,
                       const std::vector<const Image*>& frames, const std::vector<std::string>& names,
                       const RunOptions& opt);
/// The same over `count` frames asked of `frame` as the host driver reaches them (two held
/// at a time): memory does not grow with the stream.
RunResult run_lockstep(const Geometry& g, const Formats& f, VerilatedDesign& dut, int count,
                       const FeedDriver::FrameAt& frame, const std::vector<std::string>& names,
                       const RunOptions& opt);

}  // namespace hc::vl
