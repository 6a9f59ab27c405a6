// harris_top.hpp: cycle-accurate model of rtl/harris_top.vhd.
//
// One call of write() is one clock edge with write = '1': every register takes the value
// the RTL computes from the values before the edge. Stages are evaluated from the last to
// the first so that each reads its predecessor's pre-edge value. Cycles with write = '0'
// and bus reads change nothing, so they have no call. Every register is exposed.
// The datapath registers are held as LeanWord<int64_t>: the same numeric_std semantics as
// Word (property-tested against it in tests/model/spec_model_test.cpp) without Word's
// run-time checks, which Formats::validate() already guarantees; observe() returns Words.
#pragma once

#include <cstdint>

#include "model/harris/control_shift_register.hpp"
#include "model/harris/corner_shift_register.hpp"
#include "model/harris/find_max.hpp"
#include "model/harris/harris_pkg.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/input_converter_mux.hpp"
#include "model/harris/load_control.hpp"
#include "model/harris/observation.hpp"
#include "model/harris/types.hpp"
#include "model/fixed/lean_word.hpp"

namespace hc {

/// Which window a stage register holds: the write that completed the window's newest
/// column (writes count from 1), and the quadrant. write <= 0: none (zeros, reset values).
struct WindowTag {
    long write = -1;
    int quadrant = -1;
    /// The window equals the quadrant's previous processed window shifted one column left,
    /// so every stage may reuse that window's results for all but its newest column.
    bool slid = false;
    bool valid() const { return write > 0; }
};

/// Provenance of the windows held by each stage, for mismatch reports.
struct StageTags {
    WindowTag window, sobel, m, block, terms, response, delay, thresholded;
};

class HarrisTop {
public:
    HarrisTop(const Geometry& g, const Formats& f);

    /// Asynchronous reset (rst = '0'): the registers the RTL resets take their reset values;
    /// the others keep theirs.
    void reset();
    /// One bus write of a data word (4 pixels, byte q = quadrant q).
    void write(std::uint32_t data);

    bool load() const { return lc_.load; }
    bool ready() const { return mux_.ready(lc_.load); }
    std::uint8_t t() const { return ctrl_.t; }
    Word thr() const;
    bool cornerbit() const;
    /// The 32-bit value the host reads (bits 3..0 = quadrants 0..3).
    std::uint32_t corner() const { return csr_.out(); }
    Observation observe() const;

    const Geometry& geometry() const { return g_; }
    const Formats& formats() const { return f_; }
    long writes() const { return writes_; }
    const FindMax& find_max() const { return fm_; }
    const StageTags& tags() const { return tags_; }

private:
    using Reg = Lean64;
    template <int N>
    using RegMatrix = std::array<std::array<Reg, N>, N>;

    Geometry g_;
    Formats f_;
    long writes_ = 0;
    LoadControl lc_;
    InputConverterMux mux_;
    ControlShiftRegister ctrl_;
    RegMatrix<5> sx_, sy_, ma_, mb_, mc_;
    RegMatrix<3> bfa_, bfb_, bfc_;
    std::array<std::array<ResponseTermsT<Reg>, 3>, 3> terms_{};
    bool terms_defined_ = false;   // step-1 registers have no reset: 'U' until the first t(2)
    RegMatrix<3> hr_;
    FindMax fm_;
    Reg thr_reg_;   // threshold_value(fm_.max) as a register word: recomputed when max changes
    RegMatrix<3> r0_delay_, tr_;
    CornerShiftRegister csr_;
    StageTags tags_;

    // Per quadrant, the last window each stage processed and its results. A quadrant's
    // window advances one column every 7 writes; when a stage's input is the previous one
    // shifted left by a column, only the newest output column is computed (the others are
    // the previous results moved left). Exact: each output column depends only on its
    // input columns. Registers above stay the single source of the observed values.
    struct QuadrantCache {
        bool valid = false;
        Window7 window{};
        RegMatrix<5> sx, sy, ma, mb, mc;
        RegMatrix<3> bfa, bfb, bfc, hr;
        std::array<std::array<ResponseTermsT<Reg>, 3>, 3> terms{};
    };
    std::array<QuadrantCache, 4> qc_{};
    /// First output column to compute for a stage whose input carries `tag`: 0 (all), or
    /// the last column when the input slid and the cache holds the previous results.
    int first_column(const WindowTag& tag, int n) const;
    /// Recomputes thr_reg_ from fm_.max (after a reset and when find-max publishes a new max).
    void update_thr();
};

}  // namespace hc
