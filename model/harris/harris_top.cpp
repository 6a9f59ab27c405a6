#include "harris/harris_top.hpp"

#include <stdexcept>

#include "harris/block_filter.hpp"
#include "harris/local_maximum.hpp"
#include "harris/m_products.hpp"
#include "harris/sobel_x.hpp"
#include "harris/sobel_y.hpp"
#include "harris/threshold.hpp"

namespace hc {

HarrisTop::HarrisTop(const Geometry& g, const Formats& f) : g_(g), f_(f), fm_(f) {
    g_.validate();
    f_.validate();
    reset();
}

void HarrisTop::reset() {
    lc_.reset();
    mux_.reset();
    ctrl_.reset();
    const Word s0 = Word::sgn(0, f_.sobel_w), m0 = Word::sgn(0, f_.m_w()),
               b0 = Word::sgn(0, f_.bf_w()), r0 = Word::sgn(0, f_.resp_w);
    sx_ = sy_ = filled<5>(s0);
    ma_ = mb_ = mc_ = filled<5>(m0);
    bfa_ = bfb_ = bfc_ = filled<3>(b0);
    hr_ = r0_delay_ = tr_ = filled<3>(r0);
    fm_.reset(f_);
    csr_.reset();
}

Word HarrisTop::thr() const { return threshold_value(fm_.max, f_); }

bool HarrisTop::cornerbit() const { return local_maximum(tr_); }

void HarrisTop::write(std::uint32_t data) {
    ++writes_;
    // Read every pre-edge value a stage needs before any stage is updated.
    const bool ready_now = ready();
    const bool corner_now = cornerbit();
    const Word thr_now = thr();

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
            tr_[i][j] = ctrl_.en(5) ? threshold(r0_delay_[i][j], thr_now) : Word::sgn(0, f_.resp_w);
            r0_delay_[i][j] = hr_[i][j];
        }

    if (ctrl_.en(4)) fm_ = fm_.next(hr_[1][1], g_);

    if (ctrl_.en(3)) {
        if (!terms_defined_)
            throw std::logic_error("harris_response step 2 enabled before step 1 ever was");
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) hr_[i][j] = harris_response(terms_[i][j], f_);
    }
    if (ctrl_.en(2)) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                terms_[i][j] = harris_response_terms(bfa_[i][j], bfb_[i][j], bfc_[i][j], f_);
        terms_defined_ = true;
    }
    if (ctrl_.en(1)) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                bfa_[i][j] = block_filter(sub3(ma_, i, j), f_);
                bfb_[i][j] = block_filter(sub3(mb_, i, j), f_);
                bfc_[i][j] = block_filter(sub3(mc_, i, j), f_);
            }
    }
    if (ctrl_.en(0)) {
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j) {
                const MProducts m = m_products(sx_[i][j], sy_[i][j], f_);
                ma_[i][j] = m.a;
                mb_[i][j] = m.b;
                mc_[i][j] = m.c;
            }
    }
    if (ready_now) {
        if (!mux_.a_defined)
            throw std::logic_error("Sobel enabled while the window register is undefined");
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j) {
                const Pixels3 nb = sub3(mux_.a, i, j);
                sx_[i][j] = sobel_x(nb, f_);
                sy_[i][j] = sobel_y(nb, f_);
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
    o.sx = sx_;
    o.sy = sy_;
    o.ma = ma_;
    o.mb = mb_;
    o.mc = mc_;
    o.bfa = bfa_;
    o.bfb = bfb_;
    o.bfc = bfc_;
    o.hr = hr_;
    o.max = fm_.max;
    o.thr = thr();
    o.tr = tr_;
    o.cornerbit = cornerbit();
    o.corner_sr = csr_.out();
    o.corner = corner();
    return o;
}

}  // namespace hc
