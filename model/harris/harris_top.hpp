// harris_top.hpp: cycle-accurate model of rtl/harris_top.vhd.
//
// One call of write() is one clock edge with write = '1': every register takes the value
// the RTL computes from the values before the edge. Cycles with write = '0' and bus reads
// change nothing, so they have no call. Every register is exposed through observe().
//
// HarrisTop is the model's one public type. The model itself is HarrisTopT
// (harris/harris_top_t.hpp), written process by process after harris_top.vhd and templated
// on where its formats come from: HarrisTop picks, at construction, an instance compiled
// for its Formats (the thesis formats and every configuration in sweep/configs/, where each width
// is a constant) or else the instance that reads the widths at run time. Both compute the
// same registers (tests/model/harris_top_specialisation_test.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "model/harris/find_max.hpp"
#include "model/harris/harris_pkg.hpp"
#include "model/harris/observation.hpp"
#include "model/harris/types.hpp"

namespace hc {

/// Which window a stage register holds: the write that completed the window's newest
/// column (writes count from 1), and the quadrant. write <= 0: none (zeros, reset values).
struct WindowTag {
    long write = -1;
    int quadrant = -1;
    bool valid() const { return write > 0; }
};

/// Provenance of the windows held by each stage, for mismatch reports.
struct StageTags {
    WindowTag window, sobel, m, block, terms, response, delay, thresholded;
};

/// The interface every instance of the cycle model implements (see HarrisTop).
class CycleModel {
public:
    virtual ~CycleModel() = default;
    virtual void reset() = 0;
    virtual void write(std::uint32_t data) = 0;
    virtual bool load() const = 0;
    virtual bool ready() const = 0;
    virtual std::uint8_t t() const = 0;
    virtual Word thr() const = 0;
    virtual bool cornerbit() const = 0;
    virtual std::uint32_t corner() const = 0;
    virtual Observation observe() const = 0;
    virtual long writes() const = 0;
    virtual FindMax find_max() const = 0;
    /// find_max's period counter alone (find_max().count, without building its words).
    virtual long find_max_count() const = 0;
    virtual const StageTags& tags() const = 0;
    /// Every register (the image of the register set after the last edge), and its inverse.
    virtual std::string state() const = 0;
    virtual void restore(const std::string& image) = 0;
    /// Sets the write count and find-max's period counter, keeping every other register.
    virtual void rebase(long writes, long find_max_count) = 0;
};

/// How HarrisTop chooses its instance.
enum class Specialisation {
    compiled_if_any,   ///< the instance compiled for the formats, if there is one
    run_time,          ///< always the instance that reads the widths at run time
};

class HarrisTop {
public:
    HarrisTop(const Geometry& g, const Formats& f, Specialisation s = Specialisation::compiled_if_any);

    /// Asynchronous reset (rst = '0'): the registers the RTL resets take their reset values;
    /// the others keep theirs.
    void reset() { m_->reset(); }
    /// One bus write of a data word (4 pixels, byte q = quadrant q).
    void write(std::uint32_t data) { m_->write(data); }

    bool load() const { return m_->load(); }
    bool ready() const { return m_->ready(); }
    std::uint8_t t() const { return m_->t(); }
    Word thr() const { return m_->thr(); }
    bool cornerbit() const { return m_->cornerbit(); }
    /// The 32-bit value the host reads (bits 3..0 = quadrants 0..3).
    std::uint32_t corner() const { return m_->corner(); }
    Observation observe() const { return m_->observe(); }

    const Geometry& geometry() const { return g_; }
    const Formats& formats() const { return f_; }
    long writes() const { return m_->writes(); }
    FindMax find_max() const { return m_->find_max(); }
    long find_max_count() const { return m_->find_max_count(); }
    const StageTags& tags() const { return m_->tags(); }
    /// The full state: every register of harris_top (and the write count), prefixed by the
    /// geometry, the formats and the instance, as a byte string. A model of the same
    /// geometry, formats and instance restored from it computes exactly what this one
    /// computes from here on (a shard of a stream starts from it).
    std::string save_state() const;
    /// Restores save_state()'s image; std::invalid_argument when it belongs to another
    /// geometry, formats or instance, or is truncated.
    void restore_state(const std::string& image);
    /// Moves the model to another point of a stream whose control registers repeat: sets
    /// the write count and find-max's period counter (1 .. find_max_period()), keeping every
    /// other register. The data registers are then those of another point: a run from here
    /// is exact only after the pipeline and two find-max periods have flushed them (the
    /// warm-up of a checkpoint, eval.hpp).
    void rebase(long writes, long find_max_count) { m_->rebase(writes, find_max_count); }
    /// True when this model runs an instance compiled for its formats.
    bool compiled() const { return compiled_; }

private:
    Geometry g_;
    Formats f_;
    bool compiled_ = false;
    std::unique_ptr<CycleModel> m_;
};

/// True when an instance of the cycle model is compiled for these formats.
bool has_compiled_instance(const Formats& f);
/// The formats with a compiled instance: the thesis formats, then sweep/configs/*.json in order.
std::vector<Formats> compiled_formats();

}  // namespace hc
