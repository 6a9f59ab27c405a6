// harris_response.hpp: model of rtl/harris_response.vhd (combinational parts of both steps).
//
// Step 1 (t(2)): ac = a*c, bb = b*b (2*bf_w bits, exact) and
//   ktr2 = resize(tr2(top downto k_shift1), ktr_w) + resize(tr2(top downto k_shift2), ktr_w)
//   with tr2 = (a+c)^2, a+c in bf_w+1 bits: k*tr^2 with k = 2^-5 + 2^-7, each quotient floored.
// Step 2 (t(3)): r = resize(ac) - resize(bb) - resize(ktr2), all in resp_w bits, wrapping.
// Harris & Stephens (1988): R = det(M) - k tr(M)^2.
// Templates over the number type T (Word or LeanWord; T must hold 2*(bf_w+1) bits).
#pragma once

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

/// The step-1 registers of one response.
template <class T>
struct ResponseTermsT {
    T ac, bb, ktr2;
};
using ResponseTerms = ResponseTermsT<Word>;

/// tr(M) = a + c in trace_w bits (bf_w + 1: no overflow).
template <class T>
inline T harris_trace(const T& a, const T& c, const Formats& f) {
    return resize(a, f.trace_w()) + resize(c, f.trace_w());   // 16 -> 17 bits
}

template <class T>
inline ResponseTermsT<T> harris_response_terms(const T& a, const T& b, const T& c, const Formats& f) {
    const T trace = harris_trace(a, c, f);
    const T tr2 = trace * trace;                                         // 34 bits, exact
    const int top = f.trace_sq_w() - 1;
    ResponseTermsT<T> t;
    t.ac = a * c;   // 2*bf_w bits, exact
    t.bb = b * b;
    t.ktr2 = resize(slice(tr2, top, f.k_shift1), f.ktr_w) +   // floor(tr2 / 2^k_shift1)
             resize(slice(tr2, top, f.k_shift2), f.ktr_w);    // + floor(tr2 / 2^k_shift2)
    return t;
}

template <class T>
inline T harris_response(const ResponseTermsT<T>& t, const Formats& f) {
    return resize(t.ac, f.resp_w) - resize(t.bb, f.resp_w) - resize(t.ktr2, f.resp_w);
}

}  // namespace hc
