#include "model/harris/harris_top.hpp"

#include <stdexcept>

#include "model/harris/block_filter.hpp"
#include "model/harris/local_maximum.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/harris/threshold.hpp"

namespace hc {

HarrisTop::HarrisTop(const Geometry& g, const Formats& f) : g_(g), f_(f), fm_(f) {
    g_.validate();
    f_.validate();
    reset();
}

namespace {
template <int N, class T>
std::array<std::array<T, N>, N> fill(const T& v) {
    std::array<std::array<T, N>, N> m;
    for (auto& row : m) row.fill(v);
    return m;
}
template <std::size_t N, class T>
WordMatrix<static_cast<int>(N)> to_words(const std::array<std::array<T, N>, N>& m) {
    WordMatrix<static_cast<int>(N)> out;
    for (std::size_t i = 0; i < N; ++i)
        for (std::size_t j = 0; j < N; ++j) out[i][j] = Word::from_bits(m[i][j].bits(), m[i][j].width(), m[i][j].is_signed());
    return out;
}
}  // namespace

void HarrisTop::reset() {
    lc_.reset();
    mux_.reset();
    ctrl_.reset();
    const Reg s0 = Reg::sgn(0, f_.sobel_w), m0 = Reg::sgn(0, f_.m_w()), b0 = Reg::sgn(0, f_.bf_w()),
              r0 = Reg::sgn(0, f_.resp_w);
    sx_ = sy_ = fill<5>(s0);
    ma_ = mb_ = mc_ = fill<5>(m0);
    bfa_ = bfb_ = bfc_ = fill<3>(b0);
    hr_ = r0_delay_ = tr_ = fill<3>(r0);
    for (auto& q : qc_) q.valid = false;
    fm_.reset(f_);
    update_thr();
    csr_.reset();
}

Word HarrisTop::thr() const { return threshold_value(fm_.max, f_); }

void HarrisTop::update_thr() {
    const Word t = thr();
    thr_reg_ = Reg::from_bits(t.bits(), t.width(), true);
}

bool HarrisTop::cornerbit() const { return local_maximum(tr_); }

int HarrisTop::first_column(const WindowTag& tag, int n) const {
    return tag.quadrant >= 0 && tag.slid ? n - 1 : 0;
}

namespace {
/// Moves the cached previous results one column left into `out` (columns 0..n-2).
template <class M>
void slide_from(M& out, const M& prev) {
    const std::size_t n = out.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j + 1 < n; ++j) out[i][j] = prev[i][j + 1];
}
}  // namespace

void HarrisTop::write(std::uint32_t data) {
    ++writes_;
    // Read every pre-edge value a stage needs before any stage is updated.
    const bool ready_now = ready();
    const bool corner_now = cornerbit();
    const Reg thr_now = thr_reg_;

    csr_ = csr_.next(corner_now);
    const StageTags tg = tags_;
    tags_.thresholded = ctrl_.en(5) ? tg.delay : WindowTag{};
    tags_.delay = tg.response;
    if (ctrl_.en(3)) tags_.response = tg.terms;
    if (ctrl_.en(2)) tags_.terms = tg.block;
    if (ctrl_.en(1)) tags_.block = tg.m;
    if (ctrl_.en(0)) tags_.m = tg.sobel;
    if (ready_now) tags_.sobel = tg.window;
    // the mux loads quadrant i-1's window, whose newest column ended i writes ago
    tags_.window = mux_.i <= 4 ? WindowTag{writes_ - mux_.i, mux_.i - 1} : WindowTag{};

    // threshold: output from the one-write-delayed response; the delay takes hrm always
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            tr_[i][j] = ctrl_.en(5) ? threshold(r0_delay_[i][j], thr_now) : Reg::sgn(0, f_.resp_w);
            r0_delay_[i][j] = hr_[i][j];
        }

    if (ctrl_.en(4)) {
        const std::int64_t old_max = fm_.max.value();
        fm_ = fm_.next(Word::from_bits(hr_[1][1].bits(), f_.resp_w, true), g_);
        if (fm_.max.value() != old_max) update_thr();
    }

    if (ctrl_.en(3)) {
        if (!terms_defined_)
            throw std::logic_error("harris_response step 2 enabled before step 1 ever was");
        const WindowTag& t = tg.terms;
        const int j0 = first_column(t, 3);
        if (j0 > 0) slide_from(hr_, qc_[t.quadrant].hr);
        for (int i = 0; i < 3; ++i)
            for (int j = j0; j < 3; ++j) hr_[i][j] = harris_response(terms_[i][j], f_);
        if (t.quadrant >= 0) qc_[t.quadrant].hr = hr_;
    }
    if (ctrl_.en(2)) {
        const WindowTag& t = tg.block;
        const int j0 = first_column(t, 3);
        if (j0 > 0) slide_from(terms_, qc_[t.quadrant].terms);
        for (int i = 0; i < 3; ++i)
            for (int j = j0; j < 3; ++j)
                terms_[i][j] = harris_response_terms(bfa_[i][j], bfb_[i][j], bfc_[i][j], f_);
        if (t.quadrant >= 0) qc_[t.quadrant].terms = terms_;
        terms_defined_ = true;
    }
    if (ctrl_.en(1)) {
        const WindowTag& t = tg.m;
        const int j0 = first_column(t, 3);
        if (j0 > 0) {
            slide_from(bfa_, qc_[t.quadrant].bfa);
            slide_from(bfb_, qc_[t.quadrant].bfb);
            slide_from(bfc_, qc_[t.quadrant].bfc);
        }
        for (int i = 0; i < 3; ++i)
            for (int j = j0; j < 3; ++j) {
                bfa_[i][j] = block_filter(sub3(ma_, i, j), f_);
                bfb_[i][j] = block_filter(sub3(mb_, i, j), f_);
                bfc_[i][j] = block_filter(sub3(mc_, i, j), f_);
            }
        if (t.quadrant >= 0) {
            qc_[t.quadrant].bfa = bfa_;
            qc_[t.quadrant].bfb = bfb_;
            qc_[t.quadrant].bfc = bfc_;
        }
    }
    if (ctrl_.en(0)) {
        const WindowTag& t = tg.sobel;
        const int j0 = first_column(t, 5);
        if (j0 > 0) {
            slide_from(ma_, qc_[t.quadrant].ma);
            slide_from(mb_, qc_[t.quadrant].mb);
            slide_from(mc_, qc_[t.quadrant].mc);
        }
        for (int i = 0; i < 5; ++i)
            for (int j = j0; j < 5; ++j) {
                const MProductsT<Reg> m = m_products(sx_[i][j], sy_[i][j], f_);
                ma_[i][j] = m.a;
                mb_[i][j] = m.b;
                mc_[i][j] = m.c;
            }
        if (t.quadrant >= 0) {
            qc_[t.quadrant].ma = ma_;
            qc_[t.quadrant].mb = mb_;
            qc_[t.quadrant].mc = mc_;
        }
    }
    if (ready_now) {
        if (!mux_.a_defined)
            throw std::logic_error("Sobel enabled while the window register is undefined");
        // does the window continue this quadrant's previous one by exactly one column?
        const int q = tg.window.quadrant;
        bool slid = false;
        if (q >= 0 && qc_[q].valid) {
            slid = true;
            for (int r = 0; r < 7 && slid; ++r)
                for (int c = 0; c < 6; ++c)
                    if (mux_.a[r][c] != qc_[q].window[r][c + 1]) {
                        slid = false;
                        break;
                    }
        }
        tags_.sobel.slid = slid;
        const int j0 = slid ? 4 : 0;
        if (slid) {
            slide_from(sx_, qc_[q].sx);
            slide_from(sy_, qc_[q].sy);
        }
        for (int i = 0; i < 5; ++i)
            for (int j = j0; j < 5; ++j) {
                const Pixels3 nb = sub3(mux_.a, i, j);
                sx_[i][j] = sobel_x<Reg>(nb, f_);
                sy_[i][j] = sobel_y<Reg>(nb, f_);
            }
        if (q >= 0) {
            qc_[q].valid = true;
            qc_[q].window = mux_.a;
            qc_[q].sx = sx_;
            qc_[q].sy = sy_;
        }
    }
    ctrl_ = ctrl_.next(ready_now);
    mux_ = mux_.next(data);
    lc_ = lc_.next(g_);
}

Observation HarrisTop::observe() const {
    Observation o;
    o.load = lc_.load;
    o.ready = ready();
    o.t = ctrl_.t;
    o.icm = mux_.a;
    o.icm_defined = mux_.a_defined;
    o.sx = to_words(sx_);
    o.sy = to_words(sy_);
    o.ma = to_words(ma_);
    o.mb = to_words(mb_);
    o.mc = to_words(mc_);
    o.bfa = to_words(bfa_);
    o.bfb = to_words(bfb_);
    o.bfc = to_words(bfc_);
    o.hr = to_words(hr_);
    o.max = fm_.max;
    o.thr = thr();
    o.tr = to_words(tr_);
    o.cornerbit = cornerbit();
    o.corner_sr = csr_.out();
    o.corner = corner();
    return o;
}

}  // namespace hc
