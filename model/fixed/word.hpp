// word.hpp: a two's-complement word whose width and signedness travel with its value, and
// the numeric_std (IEEE 1076.3) operations the RTL uses, bit for bit.
//
// Purpose: the model never shifts or masks a plain int. Every narrowing is a named call:
//   resize(x, n)      numeric_std RESIZE: signed keeps the sign bit and the n-1 LSBs when
//                     shrinking, sign-extends when growing; unsigned keeps the n LSBs.
//   slice(x, hi, lo)  the VHDL slice x(hi downto lo); a slice of a signed is signed.
//   x * y             full precision: width wx + wy (numeric_std "*").
//   x + y, x - y, -x  width max(wx, wy), wrapping modulo 2^width (numeric_std "+", "-").
//   comparisons       by value, as numeric_std compares signed or unsigned operands.
// Widths are runtime values (1..62 bits) because the RTL takes them as generics; a Word
// holds its value already wrapped to its width.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace hc {

class Word {
public:
    constexpr Word() = default;

    /// The value `v` wrapped to `width` bits of the given signedness (VHDL to_signed /
    /// to_unsigned of an in-range value; out-of-range values wrap as the hardware would).
    static constexpr Word make(std::int64_t v, int width, bool is_signed) {
        check_width(width);
        return Word(wrap(v, width, is_signed), width, is_signed);
    }
    static constexpr Word sgn(std::int64_t v, int width) { return make(v, width, true); }
    static constexpr Word uns(std::int64_t v, int width) { return make(v, width, false); }

    /// A word from its raw bit pattern (bit 0 = LSB); bits above `width` are ignored.
    static constexpr Word from_bits(std::uint64_t bits, int width, bool is_signed) {
        check_width(width);
        return Word(wrap(static_cast<std::int64_t>(bits & mask(width)), width, is_signed),
                    width, is_signed);
    }

    /// The most negative value of a signed width: '1' followed by zeros.
    static constexpr Word most_negative(int width) {
        check_width(width);
        return Word(-(std::int64_t{1} << (width - 1)), width, true);
    }

    constexpr std::int64_t value() const { return v_; }
    constexpr int width() const { return w_; }
    constexpr bool is_signed() const { return s_; }
    /// The bit pattern, `width` bits, as the hardware holds it.
    constexpr std::uint64_t bits() const { return static_cast<std::uint64_t>(v_) & mask(w_); }
    constexpr bool bit(int i) const { return (bits() >> i) & 1U; }

    friend constexpr bool operator==(const Word& a, const Word& b) {
        return a.v_ == b.v_ && a.w_ == b.w_ && a.s_ == b.s_;
    }

    // numeric_std wraps a value into n bits: keep n LSBs, then read them back with the sign
    // convention of the type. Public because the formats code needs the same rule.
    static constexpr std::int64_t wrap(std::int64_t v, int width, bool is_signed) {
        const std::uint64_t m = mask(width);
        std::uint64_t u = static_cast<std::uint64_t>(v) & m;
        if (is_signed && width < 64 && ((u >> (width - 1)) & 1U)) u |= ~m;  // sign-extend
        return static_cast<std::int64_t>(u);
    }

    static constexpr int max_width = 62;

private:
    constexpr Word(std::int64_t v, int w, bool s) : v_(v), w_(static_cast<std::int8_t>(w)), s_(s) {}
    static constexpr std::uint64_t mask(int width) {
        return width >= 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << width) - 1U);
    }
    static constexpr void check_width(int width) {
        if (width < 1 || width > max_width)
            throw std::invalid_argument("Word width " + std::to_string(width) +
                                        " outside 1.." + std::to_string(max_width));
    }

    std::int64_t v_ = 0;
    std::int8_t w_ = 1;
    bool s_ = false;

    friend constexpr Word resize(const Word& x, int n);
    friend constexpr Word slice(const Word& x, int hi, int lo);
};

/// numeric_std RESIZE(x, n).
constexpr Word resize(const Word& x, int n) {
    Word::check_width(n);
    if (!x.s_) return Word(Word::wrap(x.v_, n, false), n, false);
    if (n >= x.w_) return Word(x.v_, n, true);  // sign extension keeps the value
    // shrinking a signed: the sign bit stays, the n-1 LSBs follow it
    const std::int64_t low = x.v_ & ((std::int64_t{1} << (n - 1)) - 1);
    return Word(x.v_ < 0 ? low - (std::int64_t{1} << (n - 1)) : low, n, true);
}

/// The VHDL slice x(hi downto lo), same signedness as x.
constexpr Word slice(const Word& x, int hi, int lo) {
    if (lo < 0 || hi < lo || hi >= x.w_)
        throw std::invalid_argument("slice(" + std::to_string(hi) + " downto " +
                                    std::to_string(lo) + ") of a " + std::to_string(x.w_) +
                                    "-bit word");
    return Word::from_bits(x.bits() >> lo, hi - lo + 1, x.s_);
}

/// signed(x) for an unsigned x: the same bits read as two's complement.
constexpr Word as_signed(const Word& x) { return Word::from_bits(x.bits(), x.width(), true); }

namespace detail {
constexpr void same_kind(const Word& a, const Word& b) {
    if (a.is_signed() != b.is_signed())
        throw std::invalid_argument("numeric_std has no operator mixing signed and unsigned");
}
constexpr int max_w(const Word& a, const Word& b) { return a.width() > b.width() ? a.width() : b.width(); }
}  // namespace detail

constexpr Word operator+(const Word& a, const Word& b) {
    detail::same_kind(a, b);
    return Word::make(a.value() + b.value(), detail::max_w(a, b), a.is_signed());
}
constexpr Word operator-(const Word& a, const Word& b) {
    detail::same_kind(a, b);
    return Word::make(a.value() - b.value(), detail::max_w(a, b), a.is_signed());
}
constexpr Word operator-(const Word& a) {
    if (!a.is_signed()) throw std::invalid_argument("numeric_std has no unary minus on unsigned");
    return Word::make(-a.value(), a.width(), true);
}
constexpr Word operator*(const Word& a, const Word& b) {
    detail::same_kind(a, b);
    return Word::make(a.value() * b.value(), a.width() + b.width(), a.is_signed());
}
constexpr bool operator<(const Word& a, const Word& b) { return a.value() < b.value(); }
constexpr bool operator>(const Word& a, const Word& b) { return a.value() > b.value(); }
constexpr bool operator<=(const Word& a, const Word& b) { return a.value() <= b.value(); }
constexpr bool operator>=(const Word& a, const Word& b) { return a.value() >= b.value(); }

}  // namespace hc
