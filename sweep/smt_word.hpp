// smt_word.hpp: a hardware word as an SMT-LIB bit-vector term with numeric_std's semantics,
// the number type on which the shared stage functions (model/harris/*.hpp) write their
// arithmetic into a solver query: the derived ranges' model route (ranges.cpp) and the
// stage-equivalence proofs (stage_equivalence.cpp) run the model's own stage functions on it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace hc::sweep {

/// A signed resize to fewer bits in the query: its source term, the widths, and a Boolean
/// term that is true where numeric_std's result (sign bit kept) and plain truncation differ.
struct SmtShrink {
    std::string source;
    int from = 0, to = 0;
    std::string overflow;
};

/// The definitions of one query, in the order they are made.
struct SmtQuery {
    std::string text;
    int next = 0;
    /// write a signed resize to fewer bits as a plain truncation (what GHDL 2.0's synthesis
    /// makes of it) instead of numeric_std's (sign bit and the LSBs)
    bool truncate_signed_shrink = false;
    std::vector<SmtShrink> shrinks;   ///< every signed shrink the query made
    /// write a sign extension as yosys's write_smt2 does (the sign bit concatenated once per
    /// added bit) rather than as sign_extend: the same terms as a netlist's, which a solver
    /// that does not rewrite one into the other (cvc5) then sees as equal
    bool yosys_sign_extend = false;
};
inline thread_local SmtQuery* smt_query = nullptr;

/// A hardware word as an SMT-LIB bit-vector term with numeric_std's semantics (the number
/// type that runs the shared stage functions to write the query): each operation defines a
/// new term in the query in scope (its bits; `s` says how they are read).
struct SmtWord {
    std::string e;
    int w = 1;
    bool s = false;
    static SmtWord def(const std::string& expr, int width, bool is_signed) {
        SmtQuery& q = *smt_query;
        std::string name = fmt::format("t{}", q.next++);
        q.text += fmt::format("(define-fun {} () (_ BitVec {}) {})\n", name, width, expr);
        return {name, width, is_signed};
    }
    /// An 8-bit pixel variable (already unsigned 8 bits).
    static SmtWord uns(const SmtWord& p, int width) {
        if (width != p.w) throw std::logic_error("SmtWord::uns: a pixel is 8 bits");
        return p;
    }
    static SmtWord constant(std::int64_t v, int width) {
        const std::uint64_t bits = width >= 64 ? static_cast<std::uint64_t>(v)
                                               : static_cast<std::uint64_t>(v) & ((std::uint64_t{1} << width) - 1);
        return def(fmt::format("(_ bv{} {})", bits, width), width, true);
    }
    /// numeric_std's to_signed(v, width) (the stage functions' T::sgn)
    static SmtWord sgn(std::int64_t v, int width) { return constant(v, width); }
    /// The most negative value of a signed width: '1' followed by zeros.
    static SmtWord most_negative(int width) {
        return def(fmt::format("(concat #b1 (_ bv0 {}))", width - 1), width, true);
    }
    int width() const { return w; }
};

/// A Boolean term of the query: what a comparison of two SmtWords gives, and what the stage
/// functions' choose() and && take (model/harris/types.hpp). Not convertible to bool.
struct SmtBool {
    std::string e;
    static SmtBool def(const std::string& expr) {
        SmtQuery& q = *smt_query;
        std::string name = fmt::format("t{}", q.next++);
        q.text += fmt::format("(define-fun {} () Bool {})\n", name, expr);
        return {name};
    }
};

inline SmtWord extend(const SmtWord& x, int n) {
    if (n == x.w) return x;
    if (x.s && smt_query->yosys_sign_extend) {
        std::string e = x.e;
        for (int k = x.w; k < n; ++k) e = fmt::format("(concat ((_ extract {0} {0}) {1}) {2})", x.w - 1, x.e, e);
        return SmtWord::def(e, n, true);
    }
    return SmtWord::def(fmt::format("((_ {}_extend {}) {})", x.s ? "sign" : "zero", n - x.w, x.e), n, x.s);
}
inline SmtWord resize(const SmtWord& x, int n) {
    if (n >= x.w) return extend(x, n);
    if (!x.s) return SmtWord::def(fmt::format("((_ extract {} 0) {})", n - 1, x.e), n, false);
    SmtQuery& q = *smt_query;
    q.shrinks.push_back({x.e, x.w, n,
                         fmt::format("(distinct ((_ extract {0} {0}) {1}) ((_ extract {2} {2}) {1}))", x.w - 1, x.e, n - 1)});
    if (q.truncate_signed_shrink) return SmtWord::def(fmt::format("((_ extract {} 0) {})", n - 1, x.e), n, true);
    if (n == 1) return SmtWord::def(fmt::format("((_ extract {0} {0}) {1})", x.w - 1, x.e), 1, true);
    // numeric_std's signed shrink: the sign bit and the n-1 LSBs
    return SmtWord::def(fmt::format("(concat ((_ extract {0} {0}) {1}) ((_ extract {2} 0) {1}))", x.w - 1, x.e, n - 2), n, true);
}
inline SmtWord slice(const SmtWord& x, int hi, int lo) {
    if (lo == 0 && hi == x.w - 1) return x;
    return SmtWord::def(fmt::format("((_ extract {} {}) {})", hi, lo, x.e), hi - lo + 1, x.s);
}
inline SmtWord as_signed(const SmtWord& x) { return {x.e, x.w, true}; }
inline SmtWord binary(const char* op, const SmtWord& a, const SmtWord& b, int n) {
    const SmtWord x = resize(a, n), y = resize(b, n);
    return SmtWord::def(fmt::format("({} {} {})", op, x.e, y.e), n, a.s);
}
inline SmtWord operator+(const SmtWord& a, const SmtWord& b) { return binary("bvadd", a, b, std::max(a.w, b.w)); }
inline SmtWord operator-(const SmtWord& a, const SmtWord& b) { return binary("bvsub", a, b, std::max(a.w, b.w)); }
inline SmtWord operator-(const SmtWord& a) { return SmtWord::def(fmt::format("(bvneg {})", a.e), a.w, true); }
inline SmtWord operator*(const SmtWord& a, const SmtWord& b) { return binary("bvmul", a, b, a.w + b.w); }   // full precision

/// numeric_std's comparison: both sides extended to the wider width, signed where `a` is.
inline SmtBool compare(const char* signed_op, const char* unsigned_op, const SmtWord& a, const SmtWord& b) {
    if (a.s != b.s) throw std::logic_error("SmtWord: a comparison of a signed with an unsigned word");
    const int n = std::max(a.w, b.w);
    const SmtWord x = extend(a, n), y = extend(b, n);
    return SmtBool::def(fmt::format("({} {} {})", a.s ? signed_op : unsigned_op, x.e, y.e));
}
inline SmtBool operator<(const SmtWord& a, const SmtWord& b) { return compare("bvslt", "bvult", a, b); }
inline SmtBool operator>(const SmtWord& a, const SmtWord& b) { return compare("bvsgt", "bvugt", a, b); }
inline SmtBool operator<=(const SmtWord& a, const SmtWord& b) { return compare("bvsle", "bvule", a, b); }
inline SmtBool operator>=(const SmtWord& a, const SmtWord& b) { return compare("bvsge", "bvuge", a, b); }
inline SmtBool operator&&(const SmtBool& a, const SmtBool& b) { return SmtBool::def(fmt::format("(and {} {})", a.e, b.e)); }

/// `c ? a : b` on the query (the stage functions' choose, model/harris/types.hpp).
inline SmtWord choose(const SmtBool& c, const SmtWord& a, const SmtWord& b) {
    if (a.w != b.w || a.s != b.s) throw std::logic_error("SmtWord: choose between words of different types");
    return SmtWord::def(fmt::format("(ite {} {} {})", c.e, a.e, b.e), a.w, a.s);
}
/// The constant `v` at x's width and signedness (the stage functions' constant_like); a value
/// that does not fit is a logic_error.
inline SmtWord constant_like(const SmtWord& x, std::int64_t v) {
    const bool fits = x.w >= 63 || (x.s ? v >= -(std::int64_t{1} << (x.w - 1)) && v < (std::int64_t{1} << (x.w - 1))
                                        : v >= 0 && v < (std::int64_t{1} << x.w));
    if (!fits) throw std::logic_error(fmt::format("SmtWord: {} does not fit a {}-bit word", v, x.w));
    const SmtWord c = SmtWord::constant(v, x.w);
    return {c.e, c.w, x.s};
}
/// A condition as a one-bit unsigned word ('1' where it holds).
inline SmtWord as_bit(const SmtBool& c) { return SmtWord::def(fmt::format("(ite {} #b1 #b0)", c.e), 1, false); }

/// The corner shift register's shift (model/harris/corner_shift_register.hpp) on the query:
/// the 6-bit word c shifted left by one, `bit` entering bit 0.
inline SmtWord shift_in(const SmtWord& c, const SmtBool& bit) {
    if (c.w != 6) throw std::logic_error("SmtWord: the corner shift register is 6 bits");
    return SmtWord::def(fmt::format("(concat ((_ extract 4 0) {}) (ite {} #b1 #b0))", c.e, bit.e), 6, false);
}

/// The cycle model's number types on the query (HarrisCycle's N, model/harris/harris_top_t.hpp):
/// every register a word of its width, the pixels 8-bit unsigned words, the bus word 32 bits.
struct SmtNumbers {
    using Front = SmtWord;
    using Back = SmtWord;
    using FrontRep = SmtWord;
    using BackRep = SmtWord;
    using Pixel = SmtWord;
    using Data = SmtWord;
    using Count = SmtWord;
    using Bit = SmtBool;
    using Bits6 = SmtWord;
    /// A register's value read as a signed word of its width (a word of another width is a
    /// logic_error: the register does not hold what the model's process expects).
    static SmtWord front(const SmtWord& v, int width) {
        if (v.w != width) throw std::logic_error(fmt::format("SmtNumbers: a {}-bit register read as {} bits", v.w, width));
        return {v.e, width, true};
    }
    static SmtWord back(const SmtWord& v, int width) { return front(v, width); }
    static SmtWord front_rep(const SmtWord& x) { return x; }
    static SmtWord back_rep(const SmtWord& x) { return x; }
    static SmtWord front_zero(int width) { return SmtWord::sgn(0, width); }
    static SmtWord back_zero(int width) { return SmtWord::sgn(0, width); }
    static SmtWord bits6_zero() { return {SmtWord::constant(0, 6).e, 6, false}; }
    static SmtWord pixel(int v) { return {SmtWord::constant(v, 8).e, 8, false}; }
    static SmtWord data(std::uint32_t v) { return {SmtWord::constant(v, 32).e, 32, false}; }
    static SmtWord byte(const SmtWord& d, int q) {
        return SmtWord::def(fmt::format("((_ extract {} {}) {})", 8 * q + 7, 8 * q, d.e), 8, false);
    }
};

}  // namespace hc::sweep
