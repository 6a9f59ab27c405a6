// harris_top_t.hpp: the cycle model of rtl/harris_top.vhd, process by process.
//
// Purpose: HarrisCycle holds every register of harris_top and steps them on write() the way
// the RTL does on a clock edge with write = '1': each process assigns its registers from
// the values before the edge, leaving those its enables hold untouched. The registers are
// kept once and updated in place, so the processes run in reverse pipeline order (each
// before the process that overwrites its inputs; write() lists the order and why). They
// are member functions named after the entity instances of harris_top.vhd (lc, icmux,
// ctrl, sx/sy, mm, bfa/bfb/bfc, hr, th, fm, thr, lm, sr). The arithmetic is the shared
// stage functions (harris/sobel_x.hpp ... harris/threshold.hpp) on the number types N
// gives: LeanWords in the cycle model (CycleNumbers), the symbolic word in the proof that
// the whole design's registers follow the model's (sweep/datapath_induction.hpp). HarrisTopT
// is the cycle model: HarrisCycle on CycleNumbers, with the co-simulation's views.
//
// FS says where the formats come from: StaticFormats<F> makes every width a compile-time
// constant (the shifts and masks of each LeanWord operation fold, and the datapath before
// the response uses 32-bit words when every width there fits), DynamicFormats reads them at
// run time (64-bit words). HarrisTop (harris/harris_top.hpp) chooses the instance.
#pragma once

#include <array>
#include <compare>
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

/// The control registers of harris_top: load control, input_converter_mux's row counter and its
/// delays, the stage enables and find_max's period counter. The model moves them on each write
/// whatever the pixels are (sweep/control_induction.hpp proves the netlist does too).
struct ControlRegisters {
    int row = 1, col = 1;                ///< lc
    bool load = true;                    ///< lc
    int i = 1;                           ///< icmux
    std::array<int, 3> i_dly{1, 1, 1};   ///< icmux: i delayed by 1, 2, 3 writes
    std::uint8_t t = 0;                  ///< ctrl
    long count = 1;                      ///< fm
    auto operator<=>(const ControlRegisters&) const = default;
};

/// The number types of the cycle model's registers (HarrisCycle's N): FS's Front and Back
/// words, kept as their bare values (FrontRep, BackRep) and read back at a register's width;
/// 8-bit pixels and 32-bit bus words (PixelNumbers); find_max's counter a long; the corner
/// bit a bool. The whole-design proof gives HarrisCycle the symbolic word's instead
/// (sweep/datapath_induction.cpp), so that the processes below run on both.
template <class FS>
struct CycleNumbers : PixelNumbers {
    using Front = typename CycleWords<FS>::Front;
    using Back = typename CycleWords<FS>::Back;
    using FrontRep = decltype(Front::v);
    using BackRep = decltype(Back::v);
    using Count = long;
    using Bit = bool;
    using Bits6 = std::uint8_t;
    static Front front(FrontRep v, int width) { return Front{v, width, true}; }
    static Back back(BackRep v, int width) { return Back{v, width, true}; }
    static FrontRep front_rep(const Front& x) { return x.v; }
    static BackRep back_rep(const Back& x) { return x.v; }
    static FrontRep front_zero(int) { return 0; }
    static BackRep back_zero(int) { return 0; }
    static Bits6 bits6_zero() { return 0; }
};

/// Every register of harris_top and its processes: one write() is one clock edge with
/// write = '1'. N gives the number types (CycleNumbers, or the whole-design proof's symbolic
/// ones); the control registers (load control, the row counters, the stage enables) are
/// plain integers in both, so the enables choose which processes run.
template <class FS, class N>
class HarrisCycle {
public:
    using Front = typename N::Front;
    using Back = typename N::Back;
    using FrontRep = typename N::FrontRep;
    using BackRep = typename N::BackRep;
    /// An N x N matrix of register values (widths in the formats), element (i, j) at i*N + j.
    template <class Rep, int M>
    using Plane = std::array<Rep, M * M>;

    /// Every register of harris_top, named as in the VHDL.
    struct Registers {
        long writes = 0;                          ///< writes so far (not a VHDL register)
        LoadControl lc;                           ///< lc: row, col, load
        InputConverterMuxT<N> icmux;              ///< icmux: i, delays, windows, a (icm)
        ControlShiftRegister ctrl;                ///< ctrl: t
        Plane<FrontRep, 5> sxm{}, sym{};          ///< sx, sy (sobel_w bits)
        Plane<FrontRep, 5> mam{}, mbm{}, mcm{};   ///< mm (m_w bits)
        Plane<FrontRep, 3> bfam{}, bfbm{}, bfcm{};   ///< bfa, bfb, bfc (bf_w bits)
        Plane<BackRep, 3> ac{}, bb{}, ktr2{};     ///< hr step 1 (prod_w, prod_w, ktr_w bits)
        bool step1_defined = false;               ///< step 1 has no reset: 'U' until t(2)
        Plane<BackRep, 3> hrm{};                  ///< hr step 2 (resp_w bits)
        Plane<BackRep, 3> r0_delay{}, trm{};      ///< th (resp_w bits)
        FindMaxT<Back, typename N::Count> fm;     ///< fm: count, running, max
        CornerShiftRegisterT<typename N::Bits6, typename N::Bit> sr;   ///< sr: corner_sr
        StageTags tags;                           ///< provenance of each stage's window

        explicit Registers(const Formats& f) : fm(f) {}
        Registers(const Formats& f, const typename N::Count& count) : fm(f, count) {}
    };

    HarrisCycle(const Geometry& g, const FS& fs) : g_(g), fs_(fs), reg_(fs.get()) { reset(); }
    HarrisCycle(const Geometry& g, const FS& fs, const typename N::Count& count) : g_(g), fs_(fs), reg_(fs.get(), count) {
        reset();
    }

    /// The reset: the registers the VHDL resets take their reset values; the others keep theirs.
    void reset() {
        const Formats& f = fs_.get();
        Registers& r = reg_;
        r.lc.reset();
        r.icmux.reset();
        r.ctrl.reset();
        for (auto* p : {&r.sxm, &r.sym}) p->fill(N::front_zero(f.sobel_w));
        for (auto* p : {&r.mam, &r.mbm, &r.mcm}) p->fill(N::front_zero(f.m_w()));
        for (auto* p : {&r.bfam, &r.bfbm, &r.bfcm}) p->fill(N::front_zero(f.bf_w()));
        for (auto* p : {&r.hrm, &r.r0_delay, &r.trm}) p->fill(N::back_zero(f.resp_w));
        r.fm.reset(f);
        r.sr.c = N::bits6_zero();
    }

    Registers& registers() { return reg_; }
    const Registers& registers() const { return reg_; }

    // The clock edge in place: each process updates its own registers from the values they
    // and their inputs held before the edge, so the processes run from the pipeline's end to
    // its start (each before the one that overwrites its inputs), the enables t and ready
    // are read before ctrl and lc move on, and a disabled stage keeps its registers
    // untouched.
    void write(const typename N::Data& data) {
        Registers& r = reg_;
        const bool ready = r.icmux.ready(r.lc.load);   // icmux's output, from lc's load
        ++r.writes;                                     // this write's number (icmux's tag)
        sr(r);       // reads trm
        th(r);       // reads fm's maximum, r0_delay, hrm
        fm(r);       // reads hrm
        hr(r);       // step 2 reads step 1's registers, step 1 reads bf
        bf(r);       // reads mm
        mm(r);       // reads sx, sy
        sx_sy(r, ready);   // reads icmux's output register
        icmux(r, data);
        ctrl(r, ready);    // t: read by every stage above
        lc(r);
    }

    /// thr: the threshold value formed from the published maximum (combinational).
    Back thr() const { return threshold_value(reg_.fm.max, fs_.get()); }

    /// lm: local_maximum of the thresholded responses (combinational): the corner bit.
    typename N::Bit cornerbit() const { return lm(reg_); }

private:
    /// The 3x3 block of a 5x5 plane whose top-left element is (i, j), as Front words.
    static std::array<std::array<Front, 3>, 3> block3(const Plane<FrontRep, 5>& p, int i, int j, int width) {
        std::array<std::array<Front, 3>, 3> b;
        for (int di = 0; di < 3; ++di)
            for (int dj = 0; dj < 3; ++dj) b[di][dj] = N::front(p[(i + di) * 5 + j + dj], width);
        return b;
    }

    // ---- the processes of harris_top, in the order of its architecture ----------------

    /// lc: load_control counts the writes of a window row and the rows of a frame.
    void lc(Registers& r) const { r.lc = r.lc.next(g_); }

    /// icmux: input_converter_mux shifts the write's pixels into the quadrants' windows and
    /// loads window i-1 into its output register (icm).
    void icmux(Registers& r, const typename N::Data& data) const {
        // the loaded window is quadrant i-1's, whose newest column ended i writes ago
        const int i = r.icmux.i;
        r.tags.window = i <= 4 ? WindowTag{r.writes - i, i - 1} : WindowTag{};
        r.icmux.advance(data);
    }

    /// ctrl: control_shift_register shifts ready into the stage enables t.
    void ctrl(Registers& r, bool ready) const { r.ctrl = r.ctrl.next(ready); }

    /// rows5/cols5 sx, sy: sobel_x and sobel_y of the 3x3 window pixels at (i..i+2, j..j+2)
    /// for the 5x5 gradients; enable: ready.
    void sx_sy(Registers& r, bool ready) const {
        if (!ready) return;
        if (!r.icmux.a_defined) throw std::logic_error("Sobel enabled while the window register is undefined");
        const Formats& f = fs_.get();
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j) {
                const auto nb = sub3(r.icmux.a, i, j);
                r.sxm[i * 5 + j] = N::front_rep(sobel_x<Front>(nb, f));
                r.sym[i * 5 + j] = N::front_rep(sobel_y<Front>(nb, f));
            }
        r.tags.sobel = r.tags.window;
    }

    /// rows5/cols5 mm: m_products of each gradient pair; enable: t(0).
    void mm(Registers& r) const {
        if (!r.ctrl.en(0)) return;
        const Formats& f = fs_.get();
        for (int k = 0; k < 25; ++k) {
            const MProductsT<Front> m = m_products(N::front(r.sxm[k], f.sobel_w), N::front(r.sym[k], f.sobel_w), f);
            r.mam[k] = N::front_rep(m.a);
            r.mbm[k] = N::front_rep(m.b);
            r.mcm[k] = N::front_rep(m.c);
        }
        r.tags.m = r.tags.sobel;
    }

    /// rows3/cols3 bfa, bfb, bfc: block_filter of the M coefficients at (i..i+2, j..j+2);
    /// enable: t(1).
    void bf(Registers& r) const {
        if (!r.ctrl.en(1)) return;
        const Formats& f = fs_.get();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                r.bfam[i * 3 + j] = N::front_rep(block_filter(block3(r.mam, i, j, f.m_w()), f));
                r.bfbm[i * 3 + j] = N::front_rep(block_filter(block3(r.mbm, i, j, f.m_w()), f));
                r.bfcm[i * 3 + j] = N::front_rep(block_filter(block3(r.mcm, i, j, f.m_w()), f));
            }
        r.tags.block = r.tags.m;
    }

    /// rows3/cols3 hr: harris_response, step 2 (the response from step 1's registers, enable
    /// t(3)), then step 1 (products and k-term, enable t(2)), which overwrites them.
    void hr(Registers& r) const {
        const Formats& f = fs_.get();
        if (r.ctrl.en(3)) {   // step2
            if (!r.step1_defined) throw std::logic_error("harris_response step 2 enabled before step 1 ever was");
            for (int k = 0; k < 9; ++k) {
                const ResponseTermsT<Back> s{N::back(r.ac[k], f.prod_w()), N::back(r.bb[k], f.prod_w()),
                                             N::back(r.ktr2[k], f.ktr_w)};
                r.hrm[k] = N::back_rep(harris_response(s, f));
            }
            r.tags.response = r.tags.terms;
        }
        if (r.ctrl.en(2)) {   // step1
            for (int k = 0; k < 9; ++k) {
                const ResponseTermsT<Back> s = harris_response_terms(
                    N::back(r.bfam[k], f.bf_w()), N::back(r.bfbm[k], f.bf_w()), N::back(r.bfcm[k], f.bf_w()), f);
                r.ac[k] = N::back_rep(s.ac);
                r.bb[k] = N::back_rep(s.bb);
                r.ktr2[k] = N::back_rep(s.ktr2);
            }
            r.step1_defined = true;
            r.tags.terms = r.tags.block;
        }
    }

    /// rows3/cols3 th: threshold delays each response by one write (r0_delay) and, on t(5),
    /// keeps the delayed response when it reaches thr (else 0); without t(5) the output is 0.
    void th(Registers& r) const {
        const Formats& f = fs_.get();
        const Back thr_q = thr();
        const bool en = r.ctrl.en(5);
        for (int k = 0; k < 9; ++k) {
            r.trm[k] = en ? N::back_rep(threshold(N::back(r.r0_delay[k], f.resp_w), thr_q)) : N::back_zero(f.resp_w);
            r.r0_delay[k] = r.hrm[k];
        }
        r.tags.thresholded = en ? r.tags.delay : WindowTag{};
        r.tags.delay = r.tags.response;
    }

    /// fm: find_max tracks the centre response hrm(2,2) on t(4) and publishes the maximum
    /// of each period.
    void fm(Registers& r) const {
        if (r.ctrl.en(4)) r.fm = r.fm.next(N::back(r.hrm[1 * 3 + 1], fs_.get().resp_w), g_);
    }

    typename N::Bit lm(const Registers& q) const {
        const Formats& f = fs_.get();
        std::array<std::array<Back, 3>, 3> r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r[i][j] = N::back(q.trm[i * 3 + j], f.resp_w);
        return local_maximum(r);
    }

    /// sr: corner_shift_register shifts the corner bit in.
    void sr(Registers& r) const { r.sr = r.sr.next(lm(r)); }

    Geometry g_;
    [[no_unique_address]] FS fs_;
    Registers reg_;   ///< every register of harris_top
};

/// The cycle model as a CycleModel: HarrisCycle on CycleNumbers, with the views the
/// co-simulation reads (observe, the state image, the control registers).
template <class FS>
class HarrisTopT final : public CycleModel {
    using Cycle = HarrisCycle<FS, CycleNumbers<FS>>;
    using Registers = typename Cycle::Registers;
    using Back = typename Cycle::Back;
    template <class Rep, int M>
    using Plane = typename Cycle::template Plane<Rep, M>;

public:
    HarrisTopT(const Geometry& g, const FS& fs) : fs_(fs), cycle_(g, fs) {}

    void reset() override { cycle_.reset(); }

    // flatten: every stage function is inlined here, so that the formats' constants reach
    // each LeanWord operation (GCC's inliner otherwise stops early in a file holding many
    // instances: docs/performance.md, cycle model).
    [[gnu::flatten]] void write(std::uint32_t data) override { cycle_.write(data); }

    bool load() const override { return q().lc.load; }
    bool ready() const override { return q().icmux.ready(q().lc.load); }
    std::uint8_t t() const override { return q().ctrl.t; }
    Word thr() const override { return word(cycle_.thr().v, fs_.get().resp_w); }
    bool cornerbit() const override { return cycle_.cornerbit(); }
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
        cycle_.registers() = r;
    }

    void rebase(long writes, long find_max_count) override {
        cycle_.registers().writes = writes;
        cycle_.registers().fm.count = find_max_count;
    }

    long find_max_count() const override { return q().fm.count; }

    ControlRegisters control() const {
        const Registers& r = q();
        return {r.lc.row, r.lc.col, r.lc.load, r.icmux.i, r.icmux.i_dly, r.ctrl.t, r.fm.count};
    }

    FindMax find_max() const override {
        const auto& m = q().fm;
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
    const Registers& q() const { return cycle_.registers(); }

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

    static Word word(std::int64_t v, int width) { return Word::sgn(v, width); }
    template <int M, class Rep>
    static WordMatrix<M> words(const Plane<Rep, M>& p, int width) {
        WordMatrix<M> m;
        for (int i = 0; i < M; ++i)
            for (int j = 0; j < M; ++j) m[i][j] = word(p[i * M + j], width);
        return m;
    }

    [[no_unique_address]] FS fs_;
    Cycle cycle_;
};

}  // namespace hc
