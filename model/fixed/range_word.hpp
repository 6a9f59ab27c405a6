// range_word.hpp: the set of values a two's-complement word can hold, as an interval, with
// the numeric_std operations of hc::Word (word.hpp): the number type that runs the shared
// stage functions (model/harris/*.hpp) as a sound range analysis.
//
// Purpose: a width is safe for every input when the exact integer each register stands for
// always fits it. RangeWord carries an interval that contains that exact ("ideal") value
// for every input, so the same template code that is the model computes, from a pixel
// interval, a bound on every register.
//
// Invariant: the hardware value of the word is congruent to its ideal value modulo
// 2^width, and the ideal value lies in [ideal.lo, ideal.hi]. When that interval fits the
// word's width and signedness, the hardware value *is* the ideal value (exact()).
// Operations that preserve congruence (+, -, unary -, unsigned shrinking resize, slice,
// signed()) keep the ideal value lazily, so a partial sum that overflows but whose total
// fits is not a wrap, as in the hardware's modular adders. Operations that do not
// (*, growing resize, signed shrinking resize: numeric_std keeps the sign bit) first
// materialise their operands: an interval that does not fit becomes the whole range of the
// width, and the narrowing is recorded in the RangeLog in scope (RangeScope).
// `id` names the hardware value: two words with the same id hold the same value, so x * x
// is a square (never negative) and not a product of two independent intervals.
// No comparisons: a branch on an interval has no single outcome (find_max and threshold()
// are bounded by the callers).
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace hc {

/// Inclusive integer interval.
struct Interval {
    std::int64_t lo = 0, hi = 0;
    friend bool operator==(const Interval&, const Interval&) = default;
};

/// What `width` bits of the given signedness can hold.
inline Interval representable(int width, bool is_signed) {
    if (width < 1 || width > 62) throw std::invalid_argument("width " + std::to_string(width) + " outside 1..62");
    if (is_signed) return {-(std::int64_t{1} << (width - 1)), (std::int64_t{1} << (width - 1)) - 1};
    return {0, (std::int64_t{1} << width) - 1};
}
inline bool fits(const Interval& v, int width, bool is_signed) {
    const Interval r = representable(width, is_signed);
    return v.lo >= r.lo && v.hi <= r.hi;
}
inline Interval hull(const Interval& a, const Interval& b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)}; }
/// floor(v / 2^n) of both ends (floor is monotone).
inline Interval floor_div_pow2(const Interval& v, int n) { return {v.lo >> n, v.hi >> n}; }

/// A narrowing whose ideal interval did not fit: the value may wrap there.
struct RangeEvent {
    Interval ideal;
    int width = 0;
    bool is_signed = true;
};
struct RangeLog {
    std::vector<RangeEvent> events;
    /// Keep the ideal interval past a narrowing that may wrap (the narrowing is still
    /// recorded): the bound of the exact value a register stands for, as opposed to what the
    /// hardware word can hold after a wrap.
    bool keep_ideal = false;
};

namespace detail {
inline RangeLog*& range_log() {
    thread_local RangeLog* log = nullptr;
    return log;
}
inline std::uint64_t next_range_id() {
    thread_local std::uint64_t n = 0;
    return ++n;
}
}  // namespace detail

/// While alive, every narrowing of a RangeWord operation on this thread that may wrap is
/// recorded in `log` (scopes nest; the innermost records).
class RangeScope {
public:
    explicit RangeScope(RangeLog& log) : prev_(detail::range_log()) { detail::range_log() = &log; }
    ~RangeScope() { detail::range_log() = prev_; }
    RangeScope(const RangeScope&) = delete;
    RangeScope& operator=(const RangeScope&) = delete;

private:
    RangeLog* prev_;
};

struct RangeWord {
    Interval ideal;
    int w = 1;
    bool s = false;
    std::uint64_t id = 0;

    /// A new hardware value whose ideal value lies in `v` (not yet checked against the width).
    static RangeWord fresh(Interval v, int width, bool is_signed) {
        (void)representable(width, is_signed);   // width check
        return {v, width, is_signed, detail::next_range_id()};
    }
    static RangeWord sgn(std::int64_t v, int width) { return materialised(fresh({v, v}, width, true)); }
    static RangeWord uns(std::int64_t v, int width) { return materialised(fresh({v, v}, width, false)); }
    /// An unsigned input (a pixel) anywhere in `v`.
    static RangeWord uns(const Interval& v, int width) { return materialised(fresh(v, width, false)); }
    static RangeWord most_negative(int width) {
        const std::int64_t m = representable(width, true).lo;
        return fresh({m, m}, width, true);
    }

    int width() const { return w; }
    bool is_signed() const { return s; }
    /// The hardware value equals the ideal one for every input.
    bool exact() const { return fits(ideal, w, s); }
    /// The values the hardware word can hold: the ideal interval when it fits, else the width's range.
    Interval held() const { return exact() ? ideal : representable(w, s); }

    /// `x` with its hardware value known: unchanged when exact, else the width's whole range
    /// (and the wrap recorded).
    static RangeWord materialised(const RangeWord& x) {
        if (x.exact()) return x;
        if (RangeLog* log = detail::range_log()) {
            log->events.push_back({x.ideal, x.w, x.s});
            if (log->keep_ideal) return x;
        }
        return {representable(x.w, x.s), x.w, x.s, x.id};
    }
};

/// numeric_std RESIZE(x, n).
inline RangeWord resize(const RangeWord& x, int n) {
    if (!x.s && n < x.w) return RangeWord::fresh(x.ideal, n, false);   // keep n LSBs: congruent mod 2^n
    const RangeWord m = RangeWord::materialised(x);
    if (n >= x.w) return {m.ideal, n, x.s, m.id};                        // extension keeps the value
    // signed shrink: the sign bit and the n-1 LSBs; the value is kept iff it fits
    return RangeWord::materialised(RangeWord{m.ideal, n, true, m.id});
}

/// x(hi downto lo): floor(x / 2^lo) modulo 2^(hi-lo+1), same signedness.
inline RangeWord slice(const RangeWord& x, int hi, int lo) {
    if (lo < 0 || hi < lo || hi >= x.w)
        throw std::invalid_argument("slice(" + std::to_string(hi) + " downto " + std::to_string(lo) + ") of a " +
                                    std::to_string(x.w) + "-bit word");
    if (lo == 0 && hi == x.w - 1) return x;
    return RangeWord::fresh(floor_div_pow2(x.ideal, lo), hi - lo + 1, x.s);
}

/// signed(x): the same bits read as two's complement (congruent: the ideal value stays).
inline RangeWord as_signed(const RangeWord& x) { return {x.ideal, x.w, true, x.id}; }

namespace detail {
inline void range_same_kind(const RangeWord& a, const RangeWord& b) {
    if (a.s != b.s) throw std::invalid_argument("numeric_std has no operator mixing signed and unsigned");
}
inline std::int64_t checked(__int128 v) {
    if (v > INT64_MAX || v < INT64_MIN) throw std::overflow_error("range bound beyond 64 bits");
    return static_cast<std::int64_t>(v);
}
}  // namespace detail

inline RangeWord operator+(const RangeWord& a, const RangeWord& b) {
    detail::range_same_kind(a, b);
    const int n = std::max(a.w, b.w);
    const RangeWord x = a.w == n ? a : resize(a, n), y = b.w == n ? b : resize(b, n);
    return RangeWord::fresh({detail::checked(__int128{x.ideal.lo} + y.ideal.lo), detail::checked(__int128{x.ideal.hi} + y.ideal.hi)},
                            n, a.s);
}
inline RangeWord operator-(const RangeWord& a) {
    if (!a.s) throw std::invalid_argument("numeric_std has no unary minus on unsigned");
    return RangeWord::fresh({-a.ideal.hi, -a.ideal.lo}, a.w, true);
}
inline RangeWord operator-(const RangeWord& a, const RangeWord& b) {
    detail::range_same_kind(a, b);
    const int n = std::max(a.w, b.w);
    const RangeWord x = a.w == n ? a : resize(a, n), y = b.w == n ? b : resize(b, n);
    return RangeWord::fresh({detail::checked(__int128{x.ideal.lo} - y.ideal.hi), detail::checked(__int128{x.ideal.hi} - y.ideal.lo)},
                            n, a.s);
}
/// Full precision (width wa + wb, never wraps); x * x of one value is a square.
inline RangeWord operator*(const RangeWord& a, const RangeWord& b) {
    detail::range_same_kind(a, b);
    const RangeWord x = RangeWord::materialised(a), y = RangeWord::materialised(b);
    const __int128 p[4] = {__int128{x.ideal.lo} * y.ideal.lo, __int128{x.ideal.lo} * y.ideal.hi,
                           __int128{x.ideal.hi} * y.ideal.lo, __int128{x.ideal.hi} * y.ideal.hi};
    __int128 lo = *std::min_element(p, p + 4), hi = *std::max_element(p, p + 4);
    if (a.id == b.id && x.ideal == y.ideal) {   // one value times itself
        const __int128 l2 = __int128{x.ideal.lo} * x.ideal.lo, h2 = __int128{x.ideal.hi} * x.ideal.hi;
        hi = std::max(l2, h2);
        lo = (x.ideal.lo <= 0 && x.ideal.hi >= 0) ? 0 : std::min(l2, h2);
    }
    return RangeWord::fresh({detail::checked(lo), detail::checked(hi)}, a.w + b.w, a.s);
}

}  // namespace hc
