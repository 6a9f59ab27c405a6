// ranges_relation.cpp: det and the response bounded through the relations one window's
// gradients impose on the block sums (see ranges.hpp, response_relation).
#include <algorithm>

#include <fmt/format.h>

#include "model/fixed/word.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "sweep/ranges.hpp"

namespace hc::sweep {

namespace {

/// max of ix^2 + iy^2 over the 3x3 windows of pixels in [0, pixel_max]: ix and iy are linear
/// in the pixels, so the sum of their squares is convex and its maximum over the box is at a
/// vertex; the 512 vertices (every pixel 0 or pixel_max) through the model's Sobel stages.
std::int64_t max_gradient_energy(const Formats& f, int pixel_max) {
    std::int64_t best = 0;
    for (int v = 0; v < 512; ++v) {
        Pixels3 nb;
        for (int k = 0; k < 9; ++k) nb[k / 3][k % 3] = static_cast<Pixel>((v >> k) & 1 ? pixel_max : 0);
        const std::int64_t ix = sobel_x<Word>(nb, f).value(), iy = sobel_y<Word>(nb, f).value();
        best = std::max(best, ix * ix + iy * iy);
    }
    return best;
}

}  // namespace

ResponseRelation response_relation(const RangeReport& rep) {
    ResponseRelation r;
    for (Reg x : {Reg::sobel_x, Reg::sobel_y, Reg::m_a, Reg::m_b, Reg::m_c, Reg::block_a, Reg::block_b, Reg::block_c, Reg::k_term})
        if (!rep.at(x).bound_fits) {
            r.why = fmt::format("not applied: {}'s interval bound does not fit (its hardware value may not be its exact value)",
                                kRegNames[static_cast<int>(x)]);
            return r;
        }
    if (rep.at(Reg::block_a).bound.lo < 0 || rep.at(Reg::block_c).bound.lo < 0) {
        r.why = "not applied: a or c may be negative";
        return r;
    }
    const Formats& f = rep.formats;
    const std::int64_t D = std::int64_t{1} << f.m_drop, E = std::int64_t{1} << f.bf_drop;
    r.energy = max_gradient_energy(f, rep.pixel_max);
    // per position ma + mc = floor(ix^2/D) + floor(iy^2/D) <= floor(energy/D); the block sums
    // a + c = floor(A/E) + floor(C/E) <= floor((A + C)/E)
    r.trace = std::min(9 * (r.energy / D) / E, rep.at(Reg::trace).bound.hi);
    r.g = 1 + (9 + E - 1) / E;
    const std::int64_t T = r.trace, g = r.g;
    // a, c >= 0 with a + c <= T; Cauchy-Schwarz: |b| < sqrt((a + g)(c + g)) + g <= T/2 + 2g
    r.ac = {0, (T / 2) * ((T + 1) / 2)};
    const std::int64_t b = std::min((T + 1) / 2 + 2 * g, std::max(-rep.at(Reg::block_b).bound.lo, rep.at(Reg::block_b).bound.hi));
    r.bb = {0, b * b};
    r.det = {-2 * g * T - 4 * g * g, r.ac.hi};
    r.ktr2 = {0, std::min(((T * T) >> f.k_shift1) + ((T * T) >> f.k_shift2), rep.at(Reg::k_term).bound.hi)};
    r.response = {r.det.lo - r.ktr2.hi, r.ac.hi};
    r.applies = true;
    const bool products = fits(r.ac, f.resp_w, true) && fits(r.bb, f.resp_w, true);
    r.det_fits = products;
    r.response_fits = products && fits(r.ktr2, f.resp_w, true) && fits(r.response, f.resp_w, true);
    r.why = fmt::format("a + c <= {0} (max ix^2 + iy^2 = {1} at a vertex of the pixel box), |b| < sqrt((a + {2})(c + {2})) + {2} "
                        "(Cauchy-Schwarz over the nine positions): a*c in [{3}, {4}], b*b in [{5}, {6}], det in [{7}, {8}], "
                        "k-term in [{9}, {10}], response in [{11}, {12}]",
                        T, r.energy, g, r.ac.lo, r.ac.hi, r.bb.lo, r.bb.hi, r.det.lo, r.det.hi, r.ktr2.lo, r.ktr2.hi, r.response.lo,
                        r.response.hi);
    return r;
}

}  // namespace hc::sweep
