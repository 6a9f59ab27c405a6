// harris_top_t.hpp: the cycle model of rtl/harris_top.vhd, process by process.
//
// Purpose: HarrisTopT holds every register of harris_top and steps them on write() the way
// the RTL does on a clock edge with write = '1': each process reads the registers before
// the edge (q) and assigns the registers after it (d), holding (d = q) those its enables
// leave unchanged. The processes are member functions named after the entity
// instances of harris_top.vhd (lc, icmux, ctrl, sx/sy, mm, bfa/bfb/bfc, hr, th, fm, thr, lm,
// sr) and are called in the order the architecture lists them. The arithmetic is the
// shared stage functions (harris/sobel_x.hpp ... harris/threshold.hpp) on LeanWords.
//
// FS says where the formats come from: StaticFormats<F> makes every width a compile-time
// constant (the shifts and masks of each LeanWord operation fold, and the datapath before
// the response uses 32-bit words when every width there fits), DynamicFormats reads them at
// run time (64-bit words). HarrisTop (harris/harris_top.hpp) chooses the instance.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <stdexcept>
#include <type_traits>

#include "model/fixed/lean_word.hpp"
#include "model/harris/block_filter.hpp"
#include "model/harris/control_shift_register.hpp"
#include "model/harris/corner_shift_register.hpp"
#include "model/harris/find_max.hpp"
#include "model/harris/harris_pkg.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/harris_top.hpp"
#include "model/harris/input_converter_mux.hpp"
#include "model/harris/load_control.hpp"
#include "model/harris/local_maximum.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/harris/threshold.hpp"

namespace hc {

/// Formats fixed at compile time.
template <Formats F>
struct StaticFormats {
    static constexpr Formats value = F;
    constexpr const Formats& get() const { return value; }
};

/// Formats read at run time.
struct DynamicFormats {
    Formats value;
    const Formats& get() const { return value; }
};

/// The number types of an instance: Front for the registers from Sobel to the block sums,
/// Back for the response terms, responses, maximum and threshold. 32-bit words hold the
/// front when its widest intermediate (ix*iy, 2*sobel_w bits; m_prod_w; bf_sum_w) fits.
template <class FS>
struct CycleWords {
    using Front = Lean64;
    using Back = Lean64;
};
template <Formats F>
struct CycleWords<StaticFormats<F>> {
    static constexpr bool front_fits_32 = 2 * F.sobel_w <= 32 && F.m_prod_w <= 32 && F.bf_sum_w <= 32;
    using Front = std::conditional_t<front_fits_32, Lean32, Lean64>;
    using Back = Lean64;
};

template <class FS>
class HarrisTopT final : public CycleModel {
    using Front = typename CycleWords<FS>::Front;
    using Back = typename CycleWords<FS>::Back;
    using FrontRep = decltype(Front::v);
    using BackRep = decltype(Back::v);
    /// An N x N matrix of register values (widths in the formats), element (i, j) at i*N + j.
    template <class Rep, int N>
    using Plane = std::array<Rep, N * N>;

    /// Every register of harris_top, named as in the VHDL.
    struct Registers {
        long writes = 0;                          ///< writes so far (not a VHDL register)
        LoadControl lc;                           ///< lc: row, col, load
        InputConverterMux icmux;                  ///< icmux: i, delays, windows, a (icm)
        ControlShiftRegister ctrl;                ///< ctrl: t
        Plane<FrontRep, 5> sxm{}, sym{};          ///< sx, sy (sobel_w bits)
        Plane<FrontRep, 5> mam{}, mbm{}, mcm{};   ///< mm (m_w bits)
        Plane<FrontRep, 3> bfam{}, bfbm{}, bfcm{};   ///< bfa, bfb, bfc (bf_w bits)
        Plane<BackRep, 3> ac{}, bb{}, ktr2{};     ///< hr step 1 (prod_w, prod_w, ktr_w bits)
        bool step1_defined = false;               ///< step 1 has no reset: 'U' until t(2)
        Plane<BackRep, 3> hrm{};                  ///< hr step 2 (resp_w bits)
        Plane<BackRep, 3> r0_delay{}, trm{};      ///< th (resp_w bits)
        FindMaxT<Back> fm;                        ///< fm: count, running, max
        CornerShiftRegister sr;                   ///< sr: corner_sr
        StageTags tags;                           ///< provenance of each stage's window

        explicit Registers(const Formats& f) : fm(f) {}
    };

public:
    HarrisTopT(const Geometry& g, const FS& fs) : g_(g), fs_(fs), reg_{Registers(fs.get()), Registers(fs.get())} {
        reset();
    }

    void reset() override {
        const Formats& f = fs_.get();
        Registers& r = reg_[cur_];
        r.lc.reset();
        r.icmux.reset();
        r.ctrl.reset();
        r.sxm = r.sym = Plane<FrontRep, 5>{};
        r.mam = r.mbm = r.mcm = Plane<FrontRep, 5>{};
        r.bfam = r.bfbm = r.bfcm = Plane<FrontRep, 3>{};
        r.hrm = r.r0_delay = r.trm = Plane<BackRep, 3>{};
        r.fm.reset(f);
        r.sr.reset();
    }

    // flatten: every stage function is inlined here, so that the formats' constants reach
    // each LeanWord operation (GCC's inliner otherwise stops early in a file holding many
    // instances: docs/performance.md, cycle model).
    [[gnu::flatten]] void write(std::uint32_t data) override {
        const Registers& q = reg_[cur_];
        Registers& d = reg_[cur_ ^ 1];
        d.writes = q.writes + 1;
        const bool ready = q.icmux.ready(q.lc.load);   // icmux's output, from lc's load
        lc(q, d);
        icmux(q, d, data);
        ctrl(q, d, ready);
        sx_sy(q, d, ready);
        mm(q, d);
        bf(q, d);
        hr(q, d);
        th(q, d);
        fm(q, d);
        sr(q, d);
        cur_ ^= 1;   // the clock edge
    }

    bool load() const override { return q().lc.load; }
    bool ready() const override { return q().icmux.ready(q().lc.load); }
    std::uint8_t t() const override { return q().ctrl.t; }
    Word thr() const override { return word(thr(q()).v, fs_.get().resp_w); }
    bool cornerbit() const override { return lm(q()); }
    std::uint32_t corner() const override { return q().sr.out(); }
    long writes() const override { return q().writes; }
    const StageTags& tags() const override { return q().tags; }

    std::string state() const override {
        std::string s;
        visit_registers(q(), [&](const auto& v) {
            s.append(reinterpret_cast<const char*>(&v), sizeof v);
        });
        return s;
    }

    void restore(const std::string& image) override {
        Registers r = q();
        std::size_t at = 0;
        visit_registers(r, [&](auto& v) {
            if (at + sizeof v > image.size())
                throw std::invalid_argument("cycle model state of " + std::to_string(image.size()) + " bytes is truncated");
            std::memcpy(&v, image.data() + at, sizeof v);
            at += sizeof v;
        });
        if (at != image.size())
            throw std::invalid_argument("cycle model state of " + std::to_string(image.size()) + " bytes, expected " +
                                        std::to_string(at));
        reg_[cur_] = r;
    }

    void rebase(long writes, long find_max_count) override {
        reg_[cur_].writes = writes;
        reg_[cur_].fm.count = find_max_count;
    }

    long find_max_count() const override { return q().fm.count; }

    FindMax find_max() const override {
        const FindMaxT<Back>& m = q().fm;
        FindMax out(fs_.get());
        out.count = m.count;
        out.running = word(m.running.v, m.running.w);
        out.max = word(m.max.v, m.max.w);
        return out;
    }

    Observation observe() const override {
        const Formats& f = fs_.get();
        const Registers& r = q();
        Observation o;
        o.load = r.lc.load;
        o.ready = ready();
        o.t = r.ctrl.t;
        o.icm = r.icmux.a;
        o.icm_defined = r.icmux.a_defined;
        o.sx = words<5>(r.sxm, f.sobel_w);
        o.sy = words<5>(r.sym, f.sobel_w);
        o.ma = words<5>(r.mam, f.m_w());
        o.mb = words<5>(r.mbm, f.m_w());
        o.mc = words<5>(r.mcm, f.m_w());
        o.bfa = words<3>(r.bfam, f.bf_w());
        o.bfb = words<3>(r.bfbm, f.bf_w());
        o.bfc = words<3>(r.bfcm, f.bf_w());
        o.hr = words<3>(r.hrm, f.resp_w);
        o.max = word(r.fm.max.v, f.resp_w);
        o.thr = thr();
        o.tr = words<3>(r.trm, f.resp_w);
        o.cornerbit = cornerbit();
        o.corner_sr = r.sr.out();
        o.corner = corner();
        return o;
    }

private:
    const Registers& q() const { return reg_[cur_]; }

    /// Calls f on every scalar of every register (arrays element by element), in one fixed
    /// order: the state image is these values' bytes, without the structs' padding.
    template <class R, class F>
    static void visit_registers(R& r, F&& f) {
        const auto each = [&](auto& x, const auto& self) -> void {
            if constexpr (std::is_arithmetic_v<std::remove_cvref_t<decltype(x)>>) {
                f(x);
            } else {
                for (auto& e : x) self(e, self);
            }
        };
        const auto v = [&](auto& x) { each(x, each); };
        const auto word = [&](auto& w) { v(w.v); v(w.w); v(w.s); };
        const auto tag = [&](auto& t) { v(t.write); v(t.quadrant); };
        v(r.writes);
        v(r.lc.row); v(r.lc.col); v(r.lc.load);
        v(r.icmux.i); v(r.icmux.i_dly); v(r.icmux.data_dly); v(r.icmux.win); v(r.icmux.a); v(r.icmux.a_defined);
        v(r.ctrl.t);
        v(r.sxm); v(r.sym); v(r.mam); v(r.mbm); v(r.mcm); v(r.bfam); v(r.bfbm); v(r.bfcm);
        v(r.ac); v(r.bb); v(r.ktr2); v(r.step1_defined); v(r.hrm); v(r.r0_delay); v(r.trm);
        v(r.fm.count); word(r.fm.running); word(r.fm.max);
        v(r.sr.c);
        tag(r.tags.window); tag(r.tags.sobel); tag(r.tags.m); tag(r.tags.block);
        tag(r.tags.terms); tag(r.tags.response); tag(r.tags.delay); tag(r.tags.thresholded);
    }

    /// A signed register value of `width` bits as a Front or Back word.
    template <class T>
    static T as(std::int64_t v, int width) {
        return T{static_cast<decltype(T::v)>(v), width, true};
    }
    static Word word(std::int64_t v, int width) { return Word::sgn(v, width); }
    template <int N, class Rep>
    static WordMatrix<N> words(const Plane<Rep, N>& p, int width) {
        WordMatrix<N> m;
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) m[i][j] = word(p[i * N + j], width);
        return m;
    }
    /// The 3x3 block of a 5x5 plane whose top-left element is (i, j), as Front words.
    static std::array<std::array<Front, 3>, 3> block3(const Plane<FrontRep, 5>& p, int i, int j, int width) {
        std::array<std::array<Front, 3>, 3> b;
        for (int di = 0; di < 3; ++di)
            for (int dj = 0; dj < 3; ++dj) b[di][dj] = as<Front>(p[(i + di) * 5 + j + dj], width);
        return b;
    }

    // ---- the processes of harris_top, in the order of its architecture ----------------

    /// lc: load_control counts the writes of a window row and the rows of a frame.
    void lc(const Registers& q, Registers& d) const { d.lc = q.lc.next(g_); }

    /// icmux: input_converter_mux shifts the write's pixels into the quadrants' windows and
    /// loads window i-1 into its output register (icm).
    void icmux(const Registers& q, Registers& d, std::uint32_t data) const {
        q.icmux.next_into(data, d.icmux);
        // the loaded window is quadrant i-1's, whose newest column ended i writes ago
        d.tags.window = q.icmux.i <= 4 ? WindowTag{d.writes - q.icmux.i, q.icmux.i - 1} : WindowTag{};
    }

    /// ctrl: control_shift_register shifts ready into the stage enables t.
    void ctrl(const Registers& q, Registers& d, bool ready) const { d.ctrl = q.ctrl.next(ready); }

    /// rows5/cols5 sx, sy: sobel_x and sobel_y of the 3x3 window pixels at (i..i+2, j..j+2)
    /// for the 5x5 gradients; enable: ready.
    void sx_sy(const Registers& q, Registers& d, bool ready) const {
        if (!ready) {
            d.sxm = q.sxm;
            d.sym = q.sym;
            d.tags.sobel = q.tags.sobel;
            return;
        }
        if (!q.icmux.a_defined) throw std::logic_error("Sobel enabled while the window register is undefined");
        const Formats& f = fs_.get();
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j) {
                const Pixels3 nb = sub3(q.icmux.a, i, j);
                d.sxm[i * 5 + j] = sobel_x<Front>(nb, f).v;
                d.sym[i * 5 + j] = sobel_y<Front>(nb, f).v;
            }
        d.tags.sobel = q.tags.window;
    }

    /// rows5/cols5 mm: m_products of each gradient pair; enable: t(0).
    void mm(const Registers& q, Registers& d) const {
        if (!q.ctrl.en(0)) {
            d.mam = q.mam;
            d.mbm = q.mbm;
            d.mcm = q.mcm;
            d.tags.m = q.tags.m;
            return;
        }
        const Formats& f = fs_.get();
        for (int k = 0; k < 25; ++k) {
            const MProductsT<Front> m = m_products(as<Front>(q.sxm[k], f.sobel_w), as<Front>(q.sym[k], f.sobel_w), f);
            d.mam[k] = m.a.v;
            d.mbm[k] = m.b.v;
            d.mcm[k] = m.c.v;
        }
        d.tags.m = q.tags.sobel;
    }

    /// rows3/cols3 bfa, bfb, bfc: block_filter of the M coefficients at (i..i+2, j..j+2);
    /// enable: t(1).
    void bf(const Registers& q, Registers& d) const {
        if (!q.ctrl.en(1)) {
            d.bfam = q.bfam;
            d.bfbm = q.bfbm;
            d.bfcm = q.bfcm;
            d.tags.block = q.tags.block;
            return;
        }
        const Formats& f = fs_.get();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                d.bfam[i * 3 + j] = block_filter(block3(q.mam, i, j, f.m_w()), f).v;
                d.bfbm[i * 3 + j] = block_filter(block3(q.mbm, i, j, f.m_w()), f).v;
                d.bfcm[i * 3 + j] = block_filter(block3(q.mcm, i, j, f.m_w()), f).v;
            }
        d.tags.block = q.tags.m;
    }

    /// rows3/cols3 hr: harris_response, step 1 (products and k-term, enable t(2)) and
    /// step 2 (the response from step 1's registers, enable t(3)).
    void hr(const Registers& q, Registers& d) const {
        const Formats& f = fs_.get();
        if (q.ctrl.en(2)) {   // step1
            for (int k = 0; k < 9; ++k) {
                const ResponseTermsT<Back> s = harris_response_terms(
                    as<Back>(q.bfam[k], f.bf_w()), as<Back>(q.bfbm[k], f.bf_w()), as<Back>(q.bfcm[k], f.bf_w()), f);
                d.ac[k] = s.ac.v;
                d.bb[k] = s.bb.v;
                d.ktr2[k] = s.ktr2.v;
            }
            d.step1_defined = true;
            d.tags.terms = q.tags.block;
        } else {
            d.ac = q.ac;
            d.bb = q.bb;
            d.ktr2 = q.ktr2;
            d.step1_defined = q.step1_defined;
            d.tags.terms = q.tags.terms;
        }
        if (q.ctrl.en(3)) {   // step2
            if (!q.step1_defined) throw std::logic_error("harris_response step 2 enabled before step 1 ever was");
            for (int k = 0; k < 9; ++k) {
                const ResponseTermsT<Back> s{as<Back>(q.ac[k], f.prod_w()), as<Back>(q.bb[k], f.prod_w()),
                                             as<Back>(q.ktr2[k], f.ktr_w)};
                d.hrm[k] = harris_response(s, f).v;
            }
            d.tags.response = q.tags.terms;
        } else {
            d.hrm = q.hrm;
            d.tags.response = q.tags.response;
        }
    }

    /// rows3/cols3 th: threshold delays each response by one write (r0_delay) and, on t(5),
    /// keeps the delayed response when it reaches thr (else 0); without t(5) the output is 0.
    void th(const Registers& q, Registers& d) const {
        const Formats& f = fs_.get();
        const Back thr_q = thr(q);
        for (int k = 0; k < 9; ++k) {
            d.trm[k] = q.ctrl.en(5) ? threshold(as<Back>(q.r0_delay[k], f.resp_w), thr_q).v : 0;
            d.r0_delay[k] = q.hrm[k];
        }
        d.tags.thresholded = q.ctrl.en(5) ? q.tags.delay : WindowTag{};
        d.tags.delay = q.tags.response;
    }

    /// fm: find_max tracks the centre response hrm(2,2) on t(4) and publishes the maximum
    /// of each period.
    void fm(const Registers& q, Registers& d) const {
        d.fm = q.ctrl.en(4) ? q.fm.next(as<Back>(q.hrm[1 * 3 + 1], fs_.get().resp_w), g_) : q.fm;
    }

    /// thr: the threshold value formed from the published maximum (combinational).
    Back thr(const Registers& q) const { return threshold_value(q.fm.max, fs_.get()); }

    /// lm: local_maximum of the thresholded responses (combinational): the corner bit.
    bool lm(const Registers& q) const {
        const Formats& f = fs_.get();
        std::array<std::array<Back, 3>, 3> r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r[i][j] = as<Back>(q.trm[i * 3 + j], f.resp_w);
        return local_maximum(r);
    }

    /// sr: corner_shift_register shifts the corner bit in.
    void sr(const Registers& q, Registers& d) const { d.sr = q.sr.next(lm(q)); }

    Geometry g_;
    [[no_unique_address]] FS fs_;
    std::array<Registers, 2> reg_;   ///< the registers before the edge (cur_) and after it
    int cur_ = 0;
};

}  // namespace hc
