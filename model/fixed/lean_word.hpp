// lean_word.hpp: a two's-complement word with the same numeric_std semantics as hc::Word
// (model/fixed/word.hpp) but no runtime checks and a fixed storage integer, so that the
// frame-level spec model can run the shared stage functions over whole images.
//
// Purpose: the stage functions (model/harris/*.hpp) are templates over the number type.
// The unit tests instantiate them with Word (checked, any width 1..62); the spec model and
// the cycle model (harris/harris_top_t.hpp) with LeanWord<int32_t> (Sobel, M, block sum,
// when every width there is <= 32) and LeanWord<int64_t> (response: (a+c)^2 needs 34 bits).
// With the Formats known at compile time every width below constant-folds and the wraps
// become two shifts the vectoriser handles.
//
// Semantics (identical to Word, property-tested in tests/model/spec_model_test.cpp):
//   make(v, w, s)      v wrapped to w bits (keep w LSBs, read back signed or unsigned)
//   resize(x, n)       numeric_std RESIZE: signed keeps sign + n-1 LSBs, unsigned n LSBs
//   slice(x, hi, lo)   x(hi downto lo), same signedness
//   + - (binary)       width max(wa, wb), wrapping;   unary -: same width, wrapping
//   *                  width wa + wb, exact
// Preconditions (not checked): every width <= bits of Rep (unsigned: < bits of Rep), and for `*` wa + wb <= bits
// of Rep; operands of + - * share a signedness.
#pragma once

#include <cstdint>
#include <type_traits>

namespace hc {

template <class Rep>
struct LeanWord {
    static_assert(std::is_same_v<Rep, std::int32_t> || std::is_same_v<Rep, std::int64_t>);
    using URep = std::make_unsigned_t<Rep>;
    static constexpr int rep_bits = 8 * sizeof(Rep);

    Rep v = 0;        ///< the value, already wrapped to w bits
    int w = 1;        ///< width in bits
    bool s = false;   ///< signed?

    /// Wrap a value held modulo 2^rep_bits to `width` bits: shift the `width` LSBs to the
    /// top and back (arithmetic for signed, logical for unsigned).
    static constexpr Rep wrap(URep u, int width, bool is_signed) {
        const int sh = rep_bits - width;
        if (is_signed) return static_cast<Rep>(static_cast<Rep>(u << sh) >> sh);
        return static_cast<Rep>(static_cast<URep>(u << sh) >> sh);
    }
    static constexpr LeanWord make(std::int64_t v, int width, bool is_signed) {
        return {wrap(static_cast<URep>(v), width, is_signed), width, is_signed};
    }
    static constexpr LeanWord sgn(std::int64_t v, int width) { return make(v, width, true); }
    static constexpr LeanWord uns(std::int64_t v, int width) { return make(v, width, false); }
    static constexpr LeanWord from_bits(std::uint64_t bits, int width, bool is_signed) {
        return make(static_cast<std::int64_t>(bits), width, is_signed);
    }
    static constexpr LeanWord most_negative(int width) {
        return {wrap(static_cast<URep>(1) << (width - 1), width, true), width, true};   // '1' then zeros
    }

    constexpr std::int64_t value() const { return v; }
    constexpr int width() const { return w; }
    constexpr bool is_signed() const { return s; }
    constexpr std::uint64_t bits() const {
        return static_cast<std::uint64_t>(static_cast<URep>(static_cast<URep>(v) << (rep_bits - w)) >>
                                          (rep_bits - w));
    }

    // numeric_std RESIZE. Signed shrink keeps the sign bit and the n-1 LSBs: take the n-1
    // LSBs as an unsigned field and subtract 2^(n-1) when the value is negative. For a
    // signed grow this is the identity (the value fits), so one formula serves both. When
    // the compiler knows the widths (formats fixed at compile time) a grow is taken as the
    // identity it is; with run-time widths that test is left out (it costs more than the
    // formula: docs/performance.md, cycle model).
    friend constexpr LeanWord resize(const LeanWord& x, int n) {
        if (__builtin_constant_p(x.s && n >= x.w) && x.s && n >= x.w) return {x.v, n, true};
        if (!x.s) return {wrap(static_cast<URep>(x.v), n, false), n, false};
        const URep low_mask = (static_cast<URep>(1) << (n - 1)) - 1U;
        const URep low = static_cast<URep>(x.v) & low_mask;
        const URep sign = x.v < 0 ? (static_cast<URep>(1) << (n - 1)) : URep{0};
        return {static_cast<Rep>(low - sign), n, true};
    }
    // x(hi downto lo): move bit hi to the top, then shift right by the field's distance to
    // bit 0 (arithmetic for signed: bit hi becomes the sign).
    friend constexpr LeanWord slice(const LeanWord& x, int hi, int lo) {
        const URep up = static_cast<URep>(x.v) << (rep_bits - 1 - hi);
        const int down = rep_bits - 1 - hi + lo;
        const Rep v = x.s ? static_cast<Rep>(static_cast<Rep>(up) >> down)
                          : static_cast<Rep>(static_cast<URep>(up >> down));
        return {v, hi - lo + 1, x.s};
    }
    friend constexpr LeanWord as_signed(const LeanWord& x) {
        return {wrap(static_cast<URep>(x.v), x.w, true), x.w, true};
    }
    friend constexpr LeanWord operator+(const LeanWord& a, const LeanWord& b) {
        const int w = a.w > b.w ? a.w : b.w;
        return {wrap(static_cast<URep>(a.v) + static_cast<URep>(b.v), w, a.s), w, a.s};
    }
    friend constexpr LeanWord operator-(const LeanWord& a, const LeanWord& b) {
        const int w = a.w > b.w ? a.w : b.w;
        return {wrap(static_cast<URep>(a.v) - static_cast<URep>(b.v), w, a.s), w, a.s};
    }
    friend constexpr LeanWord operator-(const LeanWord& a) {
        return {wrap(URep{0} - static_cast<URep>(a.v), a.w, a.s), a.w, a.s};
    }
    friend constexpr LeanWord operator*(const LeanWord& a, const LeanWord& b) {
        const int w = a.w + b.w;
        return {wrap(static_cast<URep>(a.v) * static_cast<URep>(b.v), w, a.s), w, a.s};
    }
    friend constexpr bool operator<(const LeanWord& a, const LeanWord& b) { return a.v < b.v; }
    friend constexpr bool operator>(const LeanWord& a, const LeanWord& b) { return a.v > b.v; }
    friend constexpr bool operator<=(const LeanWord& a, const LeanWord& b) { return a.v <= b.v; }
    friend constexpr bool operator>=(const LeanWord& a, const LeanWord& b) { return a.v >= b.v; }
};

using Lean32 = LeanWord<std::int32_t>;
using Lean64 = LeanWord<std::int64_t>;

}  // namespace hc
