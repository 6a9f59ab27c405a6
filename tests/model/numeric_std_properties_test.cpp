// numeric_std_properties_test.cpp: property tests of hc::Word and of every arithmetic stage
// model against a wide-integer reference.
//
// Purpose: the stage models (sobel_x, sobel_y, m_products, block_filter, harris_response,
// threshold, local_maximum) are built from hc::Word, whose operations claim numeric_std
// semantics. Here a second, deliberately naive implementation of those semantics is written
// with plain __int128 arithmetic and explicit modular wrapping, straight from the
// definitions in IEEE 1076.3 (numeric_std), and each model is compared with it for random
// inputs and random valid Formats (not only the thesis's widths):
//   RESIZE(signed, n)   every result bit starts as the argument's sign bit, then the low
//                       min(old, n) - 1 bits are copied from the argument. Shrinking
//                       therefore keeps the sign bit and the n-1 LSBs (NOT a plain
//                       modulo-2^n wrap); growing sign-extends.
//   RESIZE(unsigned, n) the n LSBs (zero-extended when growing).
//   x(hi downto lo)     floor(x / 2^lo), then read as a (hi-lo+1)-bit word of x's kind.
//   + and -             result width max(wl, wr); the value is taken modulo 2^width.
//   *                   result width wl + wr; exact.
// The reference shares no code with model/fixed/word.hpp: values are __int128, widths are
// tracked by hand next to each value, and the reference converts to int64 only to report.
// Failing properties print rapidcheck's counterexample (every generated value) and the
// logged formats.
#include <catch2/catch.hpp>
#include <rapidcheck.h>
#include <rapidcheck/catch.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

#include "model/fixed/word.hpp"
#include "model/harris/block_filter.hpp"
#include "model/harris/formats_json.hpp"
#include "model/harris/harris_pkg.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/local_maximum.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/harris/threshold.hpp"

using hc::Formats;
using hc::Word;

namespace {

// ---- the reference: numeric_std on __int128 -------------------------------------------------
namespace ref {
using i128 = __int128;

i128 p2(int n) { return i128{1} << n; }
/// The w-bit two's-complement pattern of v (v taken modulo 2^w), as a non-negative number.
i128 pattern(i128 v, int w) {
    const i128 m = p2(w);
    const i128 r = v % m;
    return r < 0 ? r + m : r;
}
/// A w-bit pattern read as a signed number.
i128 signed_of(i128 pat, int w) { return pat >= p2(w - 1) ? pat - p2(w) : pat; }
/// v modulo 2^w, read as signed: the value a w-bit signed register holds.
i128 wrap_s(i128 v, int w) { return signed_of(pattern(v, w), w); }
/// floor(v / 2^k), also for negative v.
i128 floor_div(i128 v, int k) {
    const i128 d = p2(k);
    return v >= 0 ? v / d : -((-v + d - 1) / d);
}
/// numeric_std RESIZE of a w_old-bit signed to w_new bits, bit by bit from its definition.
i128 resize_s(i128 v, int w_old, int w_new) {
    const i128 pat = pattern(v, w_old);
    const bool sign = ((pat >> (w_old - 1)) & 1) != 0;
    i128 res = sign ? p2(w_new) - 1 : 0;          // RESULT := (others => ARG(ARG'left))
    const int bound = std::min(w_old, w_new) - 2;  // BOUND := MIN(...) - 2
    if (bound >= 0) {                              // RESULT(BOUND downto 0) := ARG(BOUND downto 0)
        const i128 low = p2(bound + 1) - 1;
        res = (res & ~low) | (pat & low);
    }
    return signed_of(res, w_new);
}
/// numeric_std RESIZE of an unsigned: the w_new LSBs.
i128 resize_u(i128 v, int w_new) { return pattern(v, w_new); }
/// x(hi downto lo) of a signed x.
i128 slice_s(i128 v, int hi, int lo) { return wrap_s(floor_div(v, lo), hi - lo + 1); }

std::int64_t out(i128 v) { return static_cast<std::int64_t>(v); }   // all results fit 62 bits

// -- stage references (widths written out next to each value) --

/// Sobel x: terms -p (9 bits), -2p (10 bits), p, 2p; each RESIZEd to sw, summed modulo 2^sw.
std::int64_t sobel_x(const hc::Pixels3& a, int sw) {
    const i128 terms[6][2] = {{-i128{a[0][0]}, 9},     {-2 * i128{a[1][0]}, 10}, {-i128{a[2][0]}, 9},
                              {i128{a[0][2]}, 9},      {2 * i128{a[1][2]}, 10},  {i128{a[2][2]}, 9}};
    i128 sum = 0;
    for (const auto& t : terms) sum += resize_s(t[0], static_cast<int>(t[1]), sw);
    return out(wrap_s(sum, sw));
}
std::int64_t sobel_y(const hc::Pixels3& a, int sw) {
    const i128 terms[6][2] = {{i128{a[0][0]}, 9},      {2 * i128{a[0][1]}, 10},  {i128{a[0][2]}, 9},
                              {-i128{a[2][0]}, 9},     {-2 * i128{a[2][1]}, 10}, {-i128{a[2][2]}, 9}};
    i128 sum = 0;
    for (const auto& t : terms) sum += resize_s(t[0], static_cast<int>(t[1]), sw);
    return out(wrap_s(sum, sw));
}
/// One M product: x*y exact (wx+wy bits), RESIZE to m_prod_w, drop m_drop LSBs.
std::int64_t m_product(i128 x, i128 y, int w_in, const Formats& f) {
    const i128 full = resize_s(x * y, 2 * w_in, f.m_prod_w);
    return out(slice_s(full, f.m_prod_w - 1, f.m_drop));
}
/// Block filter: nine w_in-bit values RESIZEd to bf_sum_w, summed modulo 2^bf_sum_w,
/// bf_drop LSBs dropped.
std::int64_t block_filter(const std::array<i128, 9>& v, int w_in, const Formats& f) {
    i128 sum = 0;
    for (i128 x : v) sum += resize_s(x, w_in, f.bf_sum_w);
    return out(slice_s(wrap_s(sum, f.bf_sum_w), f.bf_sum_w - 1, f.bf_drop));
}
struct Terms {
    std::int64_t ac, bb, ktr2;
};
Terms response_terms(i128 a, i128 b, i128 c, const Formats& f) {
    const int bw = f.bf_sum_w - f.bf_drop;
    const int tw = bw + 1, t2w = 2 * tw;
    const i128 trace = wrap_s(resize_s(a, bw, tw) + resize_s(c, bw, tw), tw);
    const i128 tr2 = trace * trace;   // t2w bits, exact
    const i128 k1 = resize_s(slice_s(tr2, t2w - 1, f.k_shift1), t2w - f.k_shift1, f.ktr_w);
    const i128 k2 = resize_s(slice_s(tr2, t2w - 1, f.k_shift2), t2w - f.k_shift2, f.ktr_w);
    return {out(a * c), out(b * b), out(wrap_s(k1 + k2, f.ktr_w))};
}
std::int64_t response(i128 ac, i128 bb, i128 ktr2, const Formats& f) {
    const int pw = 2 * (f.bf_sum_w - f.bf_drop);
    const i128 r = resize_s(ac, pw, f.resp_w) - resize_s(bb, pw, f.resp_w) -
                   resize_s(ktr2, f.ktr_w, f.resp_w);
    return out(wrap_s(r, f.resp_w));
}
std::int64_t threshold_value(i128 max, const Formats& f) {
    const int top = f.resp_w - 1;
    const i128 t1 = resize_s(slice_s(max, top, f.thr_shift1), f.resp_w - f.thr_shift1, f.resp_w);
    const i128 t2 = resize_s(slice_s(max, top, f.thr_shift2), f.resp_w - f.thr_shift2, f.resp_w);
    return out(wrap_s(t1 + t2, f.resp_w));
}
}  // namespace ref

// ---- generators -----------------------------------------------------------------------------

/// Random bits, small or large, of either sign once read in a narrow width.
std::uint64_t any_bits() {
    const auto u = *rc::gen::arbitrary<std::uint64_t>();
    return *rc::gen::arbitrary<bool>() ? ~u : u;
}
int in_range(int lo, int hi_inclusive) { return *rc::gen::inRange(lo, hi_inclusive + 1); }

/// A random signed word of width w and its reference value (sign-extended independently).
struct Pair {
    Word w;
    ref::i128 v;
};
Pair signed_word(int width) {
    const std::uint64_t bits = any_bits();
    const ref::i128 pat = static_cast<ref::i128>(bits) & (ref::p2(width) - 1);
    return {Word::from_bits(bits, width, true), ref::signed_of(pat, width)};
}
Pair unsigned_word(int width) {
    const std::uint64_t bits = any_bits();
    return {Word::from_bits(bits, width, false), static_cast<ref::i128>(bits) & (ref::p2(width) - 1)};
}

/// Random formats inside Formats::validate()'s limits, with bf_w <= 30 so that (a+c)^2 fits
/// the 62-bit Word.
Formats any_formats() {
    Formats f;
    f.sobel_w = in_range(2, 30);
    f.m_prod_w = in_range(2, 62);
    f.m_drop = in_range(0, f.m_prod_w - 1);
    f.bf_sum_w = in_range(2, 40);
    f.bf_drop = in_range(std::max(0, f.bf_sum_w - 30), f.bf_sum_w - 1);
    f.resp_w = in_range(2, 62);
    f.ktr_w = in_range(1, 62);
    f.k_shift1 = in_range(0, f.trace_sq_w() - 1);
    f.k_shift2 = in_range(0, f.trace_sq_w() - 1);
    f.thr_shift1 = in_range(0, f.resp_w - 1);
    f.thr_shift2 = in_range(0, f.resp_w - 1);
    return f;
}
/// any_formats(), logged: a failing property's report names its formats.
Formats any_logged_formats() {
    const Formats f = any_formats();
    RC_LOG() << "formats " << formats_to_json(f) << "\n";
    return f;
}
hc::Pixels3 any_pixels() {
    hc::Pixels3 p;
    for (auto& row : p)
        for (auto& x : row) x = *rc::gen::arbitrary<std::uint8_t>();
    return p;
}

}  // namespace

// ---- hc::Word itself ------------------------------------------------------------------------

TEST_CASE("word: from_bits, make and as_signed read bit patterns as the reference does",
          "[model][word][property]") {
    rc::prop("from_bits and make", [] {
        const int w = in_range(1, Word::max_width);
        const std::uint64_t bits = any_bits();
        const ref::i128 pat = static_cast<ref::i128>(bits) & (ref::p2(w) - 1);
        RC_ASSERT(Word::from_bits(bits, w, true).value() == ref::out(ref::signed_of(pat, w)));
        RC_ASSERT(Word::from_bits(bits, w, false).value() == ref::out(pat));
        const auto v = static_cast<std::int64_t>(bits);
        RC_ASSERT(Word::sgn(v, w).value() == ref::out(ref::wrap_s(v, w)));
        RC_ASSERT(Word::uns(v, w).value() == ref::out(ref::pattern(v, w)));
        RC_ASSERT(as_signed(Word::from_bits(bits, w, false)).value() == ref::out(ref::signed_of(pat, w)));
        RC_ASSERT(Word::from_bits(bits, w, true).bits() == static_cast<std::uint64_t>(pat));
    });
}

TEST_CASE("word: resize matches numeric_std RESIZE for signed and unsigned, growing and shrinking",
          "[model][word][property]") {
    rc::prop("resize", [] {
        const int w = in_range(1, Word::max_width), n = in_range(1, Word::max_width);
        const Pair s = signed_word(w), u = unsigned_word(w);
        const Word rs = resize(s.w, n), ru = resize(u.w, n);
        RC_ASSERT(rs.value() == ref::out(ref::resize_s(s.v, w, n)));
        RC_ASSERT(rs.width() == n);
        RC_ASSERT(rs.is_signed());
        RC_ASSERT(ru.value() == ref::out(ref::resize_u(u.v, n)));
        RC_ASSERT(ru.width() == n);
    });
}

TEST_CASE("word: a slice floor-divides and keeps hi-lo+1 bits of the operand's kind",
          "[model][word][property]") {
    rc::prop("slice", [] {
        const int w = in_range(1, Word::max_width);
        const int hi = in_range(0, w - 1), lo = in_range(0, hi);
        const Pair s = signed_word(w), u = unsigned_word(w);
        RC_ASSERT(slice(s.w, hi, lo).value() == ref::out(ref::slice_s(s.v, hi, lo)));
        RC_ASSERT(slice(s.w, hi, lo).width() == hi - lo + 1);
        RC_ASSERT(slice(u.w, hi, lo).value() == ref::out(ref::pattern(ref::floor_div(u.v, lo), hi - lo + 1)));
        RC_ASSERT(slice(u.w, hi, lo).is_signed() == false);
    });
}

TEST_CASE("word: + and - wrap to the wider operand, unary - wraps, * is exact",
          "[model][word][property]") {
    rc::prop("signed arithmetic", [] {
        const int wa = in_range(1, Word::max_width - 1);
        const int wb = in_range(1, Word::max_width - wa);   // so that a*b fits a Word
        const Pair a = signed_word(wa), b = signed_word(wb);
        const int wm = std::max(wa, wb);
        RC_ASSERT((a.w + b.w).value() == ref::out(ref::wrap_s(a.v + b.v, wm)));
        RC_ASSERT((a.w + b.w).width() == wm);
        RC_ASSERT((a.w - b.w).value() == ref::out(ref::wrap_s(a.v - b.v, wm)));
        RC_ASSERT((a.w - b.w).width() == wm);
        RC_ASSERT((-a.w).value() == ref::out(ref::wrap_s(-a.v, wa)));
        RC_ASSERT((a.w * b.w).value() == ref::out(a.v * b.v));
        RC_ASSERT((a.w * b.w).width() == wa + wb);
        RC_ASSERT((a.w < b.w) == (a.v < b.v));
        RC_ASSERT((a.w > b.w) == (a.v > b.v));
        RC_ASSERT((a.w <= b.w) == (a.v <= b.v));
        RC_ASSERT((a.w >= b.w) == (a.v >= b.v));
    });
    rc::prop("unsigned arithmetic", [] {
        const int wa = in_range(1, Word::max_width - 1);
        const int wb = in_range(1, Word::max_width - wa);
        const Pair a = unsigned_word(wa), b = unsigned_word(wb);
        const int wm = std::max(wa, wb);
        RC_ASSERT((a.w + b.w).value() == ref::out(ref::pattern(a.v + b.v, wm)));
        RC_ASSERT((a.w - b.w).value() == ref::out(ref::pattern(a.v - b.v, wm)));
        RC_ASSERT((a.w * b.w).value() == ref::out(a.v * b.v));
        RC_ASSERT((a.w < b.w) == (a.v < b.v));
    });
}

// ---- the stages -----------------------------------------------------------------------------

TEST_CASE("sobel_x and sobel_y equal the wide-integer reference for any pixels and any sobel_w",
          "[model][sobel_x][sobel_y][property]") {
    rc::prop("sobel against reference", [] {
        Formats f;
        f.sobel_w = in_range(2, 30);
        const hc::Pixels3 px = any_pixels();
        RC_LOG() << "sobel_w=" << f.sobel_w << "\n";
        const Word ix = hc::sobel_x(px, f), iy = hc::sobel_y(px, f);
        RC_ASSERT(ix.value() == ref::sobel_x(px, f.sobel_w));
        RC_ASSERT(iy.value() == ref::sobel_y(px, f.sobel_w));
        RC_ASSERT(ix.width() == f.sobel_w);
        RC_ASSERT(iy.width() == f.sobel_w);
    });
    rc::prop("from 11 bits on, sobel is the exact kernel sum", [] {
        Formats f;
        f.sobel_w = in_range(11, 30);
        const hc::Pixels3 p = any_pixels();
        const int exact_x = (p[0][2] - p[0][0]) + 2 * (p[1][2] - p[1][0]) + (p[2][2] - p[2][0]);
        const int exact_y = (p[0][0] + 2 * p[0][1] + p[0][2]) - (p[2][0] + 2 * p[2][1] + p[2][2]);
        RC_ASSERT(hc::sobel_x(p, f).value() == exact_x);
        RC_ASSERT(hc::sobel_y(p, f).value() == exact_y);
    });
}

TEST_CASE("m_products equal the wide-integer reference for any gradients and any formats",
          "[model][m_products][property]") {
    rc::prop("m_products against reference", [] {
        const Formats f = any_logged_formats();
        const Pair ix = signed_word(f.sobel_w), iy = signed_word(f.sobel_w);
        const hc::MProducts m = hc::m_products(ix.w, iy.w, f);
        RC_ASSERT(m.a.value() == ref::m_product(ix.v, ix.v, f.sobel_w, f));
        RC_ASSERT(m.b.value() == ref::m_product(ix.v, iy.v, f.sobel_w, f));
        RC_ASSERT(m.c.value() == ref::m_product(iy.v, iy.v, f.sobel_w, f));
        RC_ASSERT(m.a.width() == f.m_w());
        RC_ASSERT(m.b.width() == f.m_w());
    });
    rc::prop("with the thesis formats and |ix|,|iy| <= 1020, M is floor(product / 32) exactly", [] {
        const Formats f;
        const int x = in_range(-1020, 1020), y = in_range(-1020, 1020);
        const hc::MProducts m = hc::m_products(Word::sgn(x, 11), Word::sgn(y, 11), f);
        RC_ASSERT(m.a.value() == ref::out(ref::floor_div(ref::i128{x} * x, 5)));
        RC_ASSERT(m.b.value() == ref::out(ref::floor_div(ref::i128{x} * y, 5)));
        RC_ASSERT(m.c.value() == ref::out(ref::floor_div(ref::i128{y} * y, 5)));
    });
}

TEST_CASE("block_filter equals the wide-integer reference for any nine inputs and any formats",
          "[model][block_filter][property]") {
    rc::prop("block_filter against reference", [] {
        const Formats f = any_logged_formats();
        hc::Matrix3 m;
        std::array<ref::i128, 9> v{};
        for (int k = 0; k < 9; ++k) {
            const Pair p = signed_word(f.m_w());
            m[k / 3][k % 3] = p.w;
            v[k] = p.v;
        }
        const Word s = hc::block_filter(m, f);
        RC_ASSERT(s.value() == ref::block_filter(v, f.m_w(), f));
        RC_ASSERT(s.width() == f.bf_w());
    });
}

TEST_CASE("harris_response_terms and harris_response equal the wide-integer reference for any formats",
          "[model][harris_response][property]") {
    rc::prop("step 1 against reference", [] {
        const Formats f = any_logged_formats();
        const Pair a = signed_word(f.bf_w()), b = signed_word(f.bf_w()), c = signed_word(f.bf_w());
        const hc::ResponseTerms t = hc::harris_response_terms(a.w, b.w, c.w, f);
        const ref::Terms r = ref::response_terms(a.v, b.v, c.v, f);
        RC_ASSERT(t.ac.value() == r.ac);
        RC_ASSERT(t.bb.value() == r.bb);
        RC_ASSERT(t.ktr2.value() == r.ktr2);
        RC_ASSERT(t.ac.width() == f.prod_w());
        RC_ASSERT(t.ktr2.width() == f.ktr_w);
    });
    rc::prop("step 2 against reference", [] {
        const Formats f = any_logged_formats();
        const Pair ac = signed_word(f.prod_w()), bb = signed_word(f.prod_w()), k = signed_word(f.ktr_w);
        const hc::ResponseTerms t{ac.w, bb.w, k.w};
        const Word r = hc::harris_response(t, f);
        RC_ASSERT(r.value() == ref::response(ac.v, bb.v, k.v, f));
        RC_ASSERT(r.width() == f.resp_w);
    });
}

TEST_CASE("threshold_value and threshold equal the wide-integer reference for any formats",
          "[model][threshold][property]") {
    rc::prop("threshold against reference", [] {
        const Formats f = any_logged_formats();
        const Pair max = signed_word(f.resp_w), r = signed_word(f.resp_w);
        const Word thr = hc::threshold_value(max.w, f);
        const std::int64_t thr_ref = ref::threshold_value(max.v, f);
        RC_ASSERT(thr.value() == thr_ref);
        RC_ASSERT(thr.width() == f.resp_w);
        const Word out = hc::threshold(r.w, thr);
        RC_ASSERT(out.value() == (r.v >= thr_ref ? ref::out(r.v) : 0));
        RC_ASSERT(out.width() == f.resp_w);
    });
}

TEST_CASE("local_maximum is true exactly when the centre is strictly above all 8 neighbours",
          "[model][local_maximum][property]") {
    rc::prop("local_maximum against reference", [] {
        // a narrow value range makes ties frequent
        const int w = in_range(2, 62);
        const int spread = in_range(1, 4);
        hc::Matrix3 m;
        ref::i128 v[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int x = in_range(-spread, spread);
                m[i][j] = Word::sgn(x, w);
                v[i][j] = ref::wrap_s(x, w);
            }
        bool strict = true;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if ((i != 1 || j != 1) && !(v[1][1] > v[i][j])) strict = false;
        RC_ASSERT(hc::local_maximum(m) == strict);
    });
}
