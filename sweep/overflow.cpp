// overflow.cpp: see overflow.hpp. Two passes per frame like the spec model (pass 1: Sobel
// and M at every interior pixel; pass 2: block sums and response), each value computed by
// the shared stage function in Lean64 and checked against the exact integer.
#include "sweep/overflow.hpp"

#include <fmt/format.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "model/harris/block_filter.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/fixed/lean_word.hpp"

namespace hc::sweep {

namespace {

/// floor(v / 2^n) for a signed integer: what dropping n LSBs of a two's-complement value
/// means. (C++20 defines >> on negative values as arithmetic, which is exactly the floor.)
constexpr std::int64_t floor_div_pow2(std::int64_t v, int n) { return v >> n; }

struct Audit {
    OverflowCounts& c;
    void check(Stage s, std::int64_t narrowed, std::int64_t exact) {
        ++c.values[s];
        if (narrowed != exact) {
            ++c.wrapped[s];
            if ((narrowed < 0) != (exact < 0)) ++c.sign_lost[s];
        }
    }
};

}  // namespace

void OverflowCounts::add(const OverflowCounts& o) {
    for (int s = 0; s < stage_count; ++s) {
        wrapped[s] += o.wrapped[s];
        sign_lost[s] += o.sign_lost[s];
        values[s] += o.values[s];
    }
}

std::uint64_t OverflowCounts::total_wrapped() const {
    std::uint64_t t = 0;
    for (auto w : wrapped) t += w;
    return t;
}

std::string OverflowCounts::summary() const {
    std::string s;
    for (int k = 0; k < stage_count; ++k)
        if (wrapped[k])
            s += fmt::format("{}{} {} (sign {})", s.empty() ? "" : ", ", kStageNames[k], wrapped[k], sign_lost[k]);
    return s;
}

OverflowCounts count_overflows(const Image& img, const Formats& f) {
    using T = Lean64;
    OverflowCounts c;
    Audit audit{c};
    const int W = img.width, H = img.height;
    if (W < 5 || H < 5) return c;
    // pass 1: Sobel and M products at every interior pixel -> planes (W-2) x (H-2)
    const int w1 = W - 2, h1 = H - 2;
    std::vector<std::int64_t> A(static_cast<size_t>(w1) * h1), B(A.size()), C(A.size());
    for (int y = 0; y < h1; ++y) {
        for (int x = 0; x < w1; ++x) {
            Pixels3 nb;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) nb[i][j] = img.at(y + i, x + j);
            // exact Sobel, the kernels of sobel_x.hpp / sobel_y.hpp: Gx = right column minus
            // left column, Gy = top row minus bottom row (centre terms doubled)
            const int gx = (nb[0][2] + 2 * nb[1][2] + nb[2][2]) - (nb[0][0] + 2 * nb[1][0] + nb[2][0]);
            const int gy = (nb[0][0] + 2 * nb[0][1] + nb[0][2]) - (nb[2][0] + 2 * nb[2][1] + nb[2][2]);
            const T ix = sobel_x<T>(nb, f), iy = sobel_y<T>(nb, f);
            audit.check(sobel, ix.v, gx);
            audit.check(sobel, iy.v, gy);
            // M: the resize of each full product (the LSB drop after it is a floor)
            const auto prod_check = [&](const T& p, const T& q) {
                audit.check(m_resize, resize(p * q, f.m_prod_w).v, p.v * q.v);
                return m_product(p, q, f).v;
            };
            const size_t o = static_cast<size_t>(y) * w1 + x;
            A[o] = prod_check(ix, ix);
            B[o] = prod_check(ix, iy);
            C[o] = prod_check(iy, iy);
        }
    }
    // pass 2: block sums and the response wherever the 3x3 M neighbourhood exists
    const int mw = f.m_w();
    for (int y = 0; y + 2 < h1; ++y) {
        for (int x = 0; x + 2 < w1; ++x) {
            const auto block = [&](const std::vector<std::int64_t>& P) {
                std::array<std::array<T, 3>, 3> n;
                std::int64_t exact = 0;
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) {
                        const std::int64_t v = P[static_cast<size_t>(y + i) * w1 + x + j];
                        n[i][j] = T{v, mw, true};   // the m_w-bit M register
                        exact += v;
                    }
                const T r = block_filter(n, f);
                audit.check(block_sum, r.v, floor_div_pow2(exact, f.bf_drop));
                return r;
            };
            const T a = block(A), b = block(B), cc = block(C);
            const ResponseTermsT<T> t = harris_response_terms(a, b, cc, f);
            const std::int64_t tr = a.v + cc.v;   // a + c in bf_w+1 bits: never wraps
            const std::int64_t tr2 = tr * tr;
            audit.check(k_term, t.ktr2.v, floor_div_pow2(tr2, f.k_shift1) + floor_div_pow2(tr2, f.k_shift2));
            audit.check(response, harris_response(t, f).v, t.ac.v - t.bb.v - t.ktr2.v);
        }
    }
    return c;
}

OverflowCounts count_overflows(const std::vector<const Image*>& frames, const Formats& f, int threads) {
    tbb::combinable<OverflowCounts> part;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(size_t{0}, frames.size(), [&](size_t i) { part.local().add(count_overflows(*frames[i], f)); });
    });
    OverflowCounts total;
    part.combine_each([&](const OverflowCounts& c) { total.add(c); });
    return total;
}

}  // namespace hc::sweep
