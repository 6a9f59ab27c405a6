// stage_benches.cpp: the seven entity benches behind stage_bridge.h.
//
// Purpose: for each arithmetic stage entity, (1) its extreme vectors, (2) how a random
// vector is drawn over the full range of its input ports, (3) the cycle schedule of its
// control inputs, and (4) the model stage function (model/harris/<stem>.hpp) that predicts
// its outputs. The register behaviour around the model function is the entity's documented
// contract (rtl/<stem>.vhd header): a value is taken on write = '1' and en = '1' and held
// otherwise; reset gives 0.
//
// Input order the testbenches read with stage_input(k) (the `in` vector of next()):
//   sobel_x, sobel_y : write, en, a11, a12, a13, a21, a22, a23, a31, a32, a33   (pixels 0..255)
//   m_products       : write, en, ix, iy
//   block_filter     : write, en, a11 .. a33                                     (row-major)
//   harris_response  : write, en0, en1, a, b, c
//   threshold        : write, en, r0, thr
//   local_maximum    : r11 .. r33                                                (row-major)
// Outputs are packed in port order, most significant bit first: ix | iy | a & b & c | sum
// | r | r1 | corner.
#include "tests/rtl/stage_bench.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "model/harris/block_filter.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/local_maximum.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/harris/threshold.hpp"
#include "tests/rtl/stage_bridge.h"

namespace hc::stage {

namespace {

using Vec = std::vector<Word>;

/// Every 16th cycle (and the first) is a hold check: the entity must ignore its inputs.
constexpr long kHoldEvery = 16;

/// Appendix A bounds (Schulz 2015): Sobel output +-1020; the M coefficients after the cut,
/// 1040400 / 32 = 32512.5, i.e. 32512 and floor(-32512.5) = -32513; the block sums after
/// the cut, 18289; the response extremes 282223846 and -668975042.
constexpr std::int64_t kSobelMax = 1020;
constexpr std::int64_t kMMax = 32512, kMMin = -32513;
constexpr std::int64_t kBfMax = 18289;
constexpr std::int64_t kRespMax = 282223846, kRespMin = -668975042;

/// Appendix A argmax/argmin windows (row-major a11..a33) of Ix and Iy: +-1020.
const std::vector<std::array<int, 9>> kAppendixAWindows = {
    {0, 0, 255, 0, 0, 255, 0, 0, 255},   // argmax Ix = +1020
    {255, 0, 0, 255, 0, 0, 255, 0, 0},   // argmin Ix = -1020
    {255, 255, 255, 0, 0, 0, 0, 0, 0},   // argmax Iy = +1020
    {0, 0, 0, 0, 0, 0, 255, 255, 255}};  // argmin Iy = -1020

std::string matrix_text(const Vec& v, std::size_t first) {
    std::ostringstream s;
    s << '[';
    for (std::size_t k = 0; k < 9; ++k)
        s << v[first + k].value() << (k == 8 ? "]" : (k % 3 == 2 ? "; " : " "));
    return s.str();
}

std::array<std::array<Word, 3>, 3> matrix3(const Vec& v) {
    std::array<std::array<Word, 3>, 3> m;
    for (int k = 0; k < 9; ++k) m[k / 3][k % 3] = v[k];
    return m;
}

/// All 512 3x3 windows whose elements are `lo` or `hi` (bit k of the index picks element k).
void add_two_level_windows(std::vector<Vec>& out, const Word& lo, const Word& hi) {
    for (int pattern = 0; pattern < 512; ++pattern) {
        Vec v;
        for (int k = 0; k < 9; ++k) v.push_back((pattern >> k) & 1 ? hi : lo);
        out.push_back(v);
    }
}

/// The (lo, hi) pairs whose two-level windows reach the corners of a signed range: the
/// full swing, the steps around 0, and the single steps at both ends.
std::vector<std::pair<std::int64_t, std::int64_t>> level_pairs(int width) {
    const std::int64_t mn = Word::most_negative(width).value(), mx = -(mn + 1);
    return {{mn, mx}, {-1, 0}, {0, 1}, {mx - 1, mx}, {mn, mn + 1}};
}

/// Common part of every bench: its extreme vectors in order, then its random vectors.
class VectorBench : public Bench {
public:
    VectorBench(const Formats& f, long random, std::uint64_t seed) : f_(f), n_random_(random), rng_(seed) {}

protected:
    /// Called once by the derived constructor.
    void set_extremes(std::vector<Vec> e) {
        extremes_ = std::move(e);
        counts_.extremes = static_cast<long>(extremes_.size());
        counts_.random = n_random_;
    }
    virtual Vec random_vector() = 0;

    long total() const { return static_cast<long>(extremes_.size()) + n_random_; }
    bool more() const { return taken_ < total(); }
    /// The next vector of the run and its index; false when all are taken.
    bool take(Vec& v, long& index) {
        if (!more()) return false;
        index = taken_;
        v = taken_ < static_cast<long>(extremes_.size()) ? extremes_[taken_] : random_vector();
        ++taken_;
        return true;
    }
    /// Whether the cycle about to be prepared is a hold check, and which kind (0 or 1).
    bool hold_due() const { return cycle_ == 0 || cycle_ % kHoldEvery == kHoldEvery - 1; }
    int hold_kind() const { return static_cast<int>((cycle_ / kHoldEvery) % 2); }

    /// A vector between its two writes, in a bench of a one-write-delay entity
    /// (harris_response, threshold): its index and inputs.
    struct Pending {
        long index;
        Vec inputs;
    };

    Formats f_;
    long n_random_;
    Rng rng_;
    std::vector<Vec> extremes_;
    long taken_ = 0;
    long cycle_ = 0;
    /// The values at and beside the ends of an input's range (signed_edges) that a bench's
    /// extreme and random vectors pick from, for the benches that use them.
    std::vector<std::int64_t> edges_;
    std::optional<Pending> pending_;   ///< one-write-delay benches: the vector awaiting its second write
};

// ---- single-register stages: sobel_x, sobel_y, m_products, block_filter -----------------

/// in = write, en, inputs...; the output register takes model(inputs) on write and en.
/// Hold checks alternate write = '0' (en = '1') and write = '1' (en = '0'), with fresh random
/// inputs the entity must ignore. The first cycle is a hold check of the reset value 0.
class RegisteredBench : public VectorBench {
public:
    using VectorBench::VectorBench;

    bool next(std::vector<std::int32_t>& in) override {
        Vec v;
        int write = 1, en = 1;
        completes_ = false;
        if (hold_due() && more()) {
            v = random_vector();
            (hold_kind() == 0 ? write : en) = 0;
            kind_ = write == 0 ? "hold check (write = '0')" : "hold check (en = '0')";
            ++counts_.holds;
        } else {
            long index;
            if (!take(v, index)) return false;
            expected_ = {model(v), index, v};
            completes_ = true;
            kind_ = "vector check";
        }
        in.clear();
        in.push_back(write);
        in.push_back(en);
        for (const Word& w : v) in.push_back(static_cast<std::int32_t>(w.value()));
        ++cycle_;
        return true;
    }

protected:
    /// The first expected value: every output at its reset value 0.
    void expect_reset(const std::vector<int>& widths) {
        for (int w : widths) expected_.out.push_back(Word::sgn(0, w));
    }
    virtual Vec model(const Vec& inputs) const = 0;
};

/// sobel_x / sobel_y: nine pixels -> one SOBEL_W gradient.
class SobelBench final : public RegisteredBench {
public:
    SobelBench(bool y, const Formats& f, long random, std::uint64_t seed)
        : RegisteredBench(f, random, seed), y_(y) {
        std::vector<Vec> e;
        for (const auto& w : kAppendixAWindows) {
            Vec v;
            for (int p : w) v.push_back(Word::uns(p, 8));
            e.push_back(v);
        }
        // all 512 black/white windows: all-0, all-255 and every sign pattern of the kernel
        add_two_level_windows(e, Word::uns(0, 8), Word::uns(255, 8));
        for (int p : {1, 127, 128, 254}) e.push_back(Vec(9, Word::uns(p, 8)));  // flat: 0
        set_extremes(std::move(e));
        expect_reset({f.sobel_w});
    }
    const char* name() const override { return y_ ? "sobel_y" : "sobel_x"; }
    int out_width() const override { return f_.sobel_w; }
    int widest_input() const override { return 8; }
    std::vector<std::string> output_names() const override { return {y_ ? "iy" : "ix"}; }
    std::string describe(const Vec& v) const override { return "a=" + matrix_text(v, 0); }

private:
    Vec random_vector() override {
        // each pixel uniform over 0..255; one pixel in 8 forced to 0 or 255, so that
        // saturated windows are not left to the 512 extremes alone
        Vec v;
        for (int k = 0; k < 9; ++k)
            v.push_back(rng_.in_range(0, 7) == 0 ? Word::uns(255 * rng_.in_range(0, 1), 8)
                                                  : rng_.any_unsigned(8));
        return v;
    }
    Vec model(const Vec& v) const override {
        Pixels3 p;
        for (int k = 0; k < 9; ++k) p[k / 3][k % 3] = static_cast<Pixel>(v[k].value());
        return {y_ ? sobel_y(p, f_) : sobel_x(p, f_)};
    }
    bool y_;
};

/// m_products: ix, iy over every SOBEL_W-bit value (not only the +-1020 a Sobel gives, so
/// numeric_std's resize wrap of the products is exercised) -> a, b, c.
class MProductsBench final : public RegisteredBench {
public:
    MProductsBench(const Formats& f, long random, std::uint64_t seed) : RegisteredBench(f, random, seed) {
        edges_ = signed_edges(f.sobel_w, {-kSobelMax, kSobelMax});
        std::vector<Vec> e;
        for (std::int64_t x : edges_)   // includes appendix A's argmax/argmin pairs
            for (std::int64_t y : edges_) e.push_back({Word::sgn(x, f.sobel_w), Word::sgn(y, f.sobel_w)});
        set_extremes(std::move(e));
        expect_reset({f.m_w(), f.m_w(), f.m_w()});
    }
    const char* name() const override { return "m_products"; }
    int out_width() const override { return 3 * f_.m_w(); }
    int widest_input() const override { return f_.sobel_w; }
    std::vector<std::string> output_names() const override { return {"a", "b", "c"}; }
    std::string describe(const Vec& v) const override {
        return "ix=" + std::to_string(v[0].value()) + " iy=" + std::to_string(v[1].value());
    }

private:
    Vec random_vector() override {
        // each gradient uniform over the port's range; one in 4 an extreme value
        Vec v;
        for (int k = 0; k < 2; ++k)
            v.push_back(rng_.in_range(0, 3) == 0 ? Word::sgn(rng_.pick(edges_), f_.sobel_w)
                                                  : rng_.any_signed(f_.sobel_w));
        return v;
    }
    Vec model(const Vec& v) const override {
        const MProducts m = m_products(v[0], v[1], f_);
        return {m.a, m.b, m.c};
    }
};

/// block_filter: nine IN_W coefficients -> one box sum with BF_DROP LSBs dropped.
class BlockFilterBench final : public RegisteredBench {
public:
    BlockFilterBench(const Formats& f, long random, std::uint64_t seed) : RegisteredBench(f, random, seed) {
        const int w = f.m_w();
        edges_ = signed_edges(w, {kMMin, kMMax});
        std::vector<Vec> e;
        for (const auto& [lo, hi] : level_pairs(w)) add_two_level_windows(e, Word::sgn(lo, w), Word::sgn(hi, w));
        for (std::int64_t x : edges_) e.push_back(Vec(9, Word::sgn(x, w)));   // flat windows
        set_extremes(std::move(e));
        expect_reset({f.bf_w()});
    }
    const char* name() const override { return "block_filter"; }
    int out_width() const override { return f_.bf_w(); }
    int widest_input() const override { return f_.m_w(); }
    std::vector<std::string> output_names() const override { return {"sum"}; }
    std::string describe(const Vec& v) const override { return "a=" + matrix_text(v, 0); }

private:
    Vec random_vector() override {
        // three vectors in 4 uniform over the port's range, one in 4 from the extreme values
        const bool edges = rng_.in_range(0, 3) == 0;
        Vec v;
        for (int k = 0; k < 9; ++k)
            v.push_back(edges ? Word::sgn(rng_.pick(edges_), f_.m_w()) : rng_.any_signed(f_.m_w()));
        return v;
    }
    Vec model(const Vec& v) const override { return {block_filter(matrix3(v), f_)}; }
};

// ---- harris_response: two register steps ------------------------------------------------

/// in = write, en0, en1, a, b, c. Pipelined: each write applies a new vector with en0 = '1'
/// (step 1 registers a*c, b*b and the k-term) and en1 = '1' (step 2 registers r from the
/// previous vector's step-1 registers), so r after a write is the previous vector's response.
/// The first vector goes in with en1 = '0' (the step-1 registers have no reset and are 'U'
/// until then) and a last write with en0 = '0', en1 = '1' flushes the final vector. Hold
/// checks: write = '0' with both enables '1', or write = '1' with both enables '0'.
class HarrisResponseBench final : public VectorBench {
public:
    HarrisResponseBench(const Formats& f, long random, std::uint64_t seed) : VectorBench(f, random, seed) {
        const int w = f.bf_w();
        edges_ = signed_edges(w, {-kBfMax, kBfMax});
        std::vector<Vec> e;
        // appendix A argmax {-18289, 0, -18289} and argmin {-18289, -18289, 18289} of r are
        // among these 9^3 combinations
        for (std::int64_t a : edges_)
            for (std::int64_t b : edges_)
                for (std::int64_t c : edges_) e.push_back({Word::sgn(a, w), Word::sgn(b, w), Word::sgn(c, w)});
        set_extremes(std::move(e));
        expected_.out = {Word::sgn(0, f.resp_w)};
    }
    const char* name() const override { return "harris_response"; }
    int out_width() const override { return f_.resp_w; }
    int widest_input() const override { return f_.bf_w(); }
    std::vector<std::string> output_names() const override { return {"r"}; }
    std::string describe(const Vec& v) const override {
        return "a=" + std::to_string(v[0].value()) + " b=" + std::to_string(v[1].value()) +
               " c=" + std::to_string(v[2].value());
    }

    bool next(std::vector<std::int32_t>& in) override {
        Vec v;
        int write = 1, en0 = 1, en1 = 1;
        completes_ = false;
        if (hold_due() && (more() || pending_)) {
            v = random_vector();
            if (hold_kind() == 0) write = 0; else en0 = en1 = 0;
            kind_ = write == 0 ? "hold check (write = '0')" : "hold check (en0 = en1 = '0')";
            ++counts_.holds;
        } else {
            long index = -1;
            const bool got = take(v, index);
            if (!got && !pending_) return false;
            en0 = got ? 1 : 0;
            en1 = pending_ ? 1 : 0;
            kind_ = pending_ ? "vector check: step 2, with the next vector's step 1" : "first step 1, en1 = '0'";
            if (pending_) {   // step 2 of the previous vector
                const Vec& p = pending_->inputs;
                expected_ = {{harris_response(harris_response_terms(p[0], p[1], p[2], f_), f_)}, pending_->index, p};
                completes_ = true;
            }
            if (got)          // step 1 of this one
                pending_ = Pending{index, v};
            else {
                pending_.reset();
                v = Vec(3, Word::sgn(0, f_.bf_w()));   // ignored: en0 = '0'
            }
        }
        in = {write, en0, en1};
        for (const Word& x : v) in.push_back(static_cast<std::int32_t>(x.value()));
        ++cycle_;
        return true;
    }

private:
    Vec random_vector() override {
        // half uniform over the port's range, a quarter within the +-18289 a block filter
        // can deliver (appendix A), a quarter from the extreme values
        const int w = f_.bf_w();
        const long mode = rng_.in_range(0, 3);
        Vec v;
        for (int k = 0; k < 3; ++k) {
            if (mode <= 1) v.push_back(rng_.any_signed(w));
            else if (mode == 2) v.push_back(Word::sgn(rng_.in_range(-kBfMax, kBfMax), w));
            else v.push_back(Word::sgn(rng_.pick(edges_), w));
        }
        return v;
    }
};

// ---- threshold: one-write delay of r0 ---------------------------------------------------

/// in = write, en, r0, thr. The entity delays r0 by one write and compares the delayed value
/// with the *current* thr, so vector (r, thr) is applied as r0 = r on one write and thr = thr
/// on the next, which carries en = '1' and also applies the next vector's r. Its output:
/// threshold(r, thr) (model/harris/threshold.hpp). The first vector's r goes in with
/// en = '0' (output 0), a last write flushes the final vector. Hold checks: write = '0'
/// (everything holds), or write = '1' with en = '0', which must clear r1 to 0 (the pending
/// r is re-applied so that no vector is lost).
class ThresholdBench final : public VectorBench {
public:
    ThresholdBench(const Formats& f, long random, std::uint64_t seed) : VectorBench(f, random, seed) {
        const int w = f.resp_w;
        edges_ = signed_edges(w, {kRespMin, kRespMax});
        std::vector<Vec> e;
        for (std::int64_t r : edges_)
            for (std::int64_t t : edges_) e.push_back({Word::sgn(r, w), Word::sgn(t, w)});
        for (std::int64_t t : edges_)      // equal (kept) and one below (zeroed) at every edge
            for (std::int64_t d : {0, -1, 1})
                if (Word::sgn(t + d, w).value() == t + d) e.push_back({Word::sgn(t + d, w), Word::sgn(t, w)});
        set_extremes(std::move(e));
        expected_.out = {Word::sgn(0, w)};
    }
    const char* name() const override { return "threshold"; }
    int out_width() const override { return f_.resp_w; }
    int widest_input() const override { return f_.resp_w; }
    std::vector<std::string> output_names() const override { return {"r1"}; }
    std::string describe(const Vec& v) const override {
        return "r0=" + std::to_string(v[0].value()) + " thr=" + std::to_string(v[1].value());
    }

    bool next(std::vector<std::int32_t>& in) override {
        const int w = f_.resp_w;
        const Word zero = Word::sgn(0, w);
        completes_ = false;
        if (hold_due() && (more() || pending_)) {
            const Vec junk = random_vector();
            ++counts_.holds;
            if (hold_kind() == 0 || !pending_) {   // write = '0': nothing moves
                in = {0, 1, to_int(junk[0]), to_int(junk[1])};
                kind_ = "hold check (write = '0')";
            } else {                                // en = '0' clears r1; r0 re-applied
                in = {1, 0, to_int(pending_->inputs[0]), to_int(junk[1])};
                expected_ = {{zero}, -1, {}, "r1 cleared by en = '0'"};
                kind_ = "clear check (en = '0')";
            }
        } else {
            Vec v;
            long index = -1;
            const bool got = take(v, index);
            if (!got && !pending_) return false;
            if (!pending_) {   // first vector: its r enters the delay register, en = '0'
                in = {1, 0, to_int(v[0]), 0};
                expected_ = {{zero}, -1, {}, "r1 cleared by en = '0'"};
                kind_ = "first r0, en = '0'";
            } else {
                in = {1, 1, got ? to_int(v[0]) : 0, to_int(pending_->inputs[1])};
                expected_ = {{threshold(pending_->inputs[0], pending_->inputs[1])}, pending_->index,
                             pending_->inputs};
                completes_ = true;
                kind_ = "vector check: thr with en = '1', the next vector's r0";
            }
            if (got) pending_ = Pending{index, v};
            else pending_.reset();
        }
        ++cycle_;
        return true;
    }

private:
    static std::int32_t to_int(const Word& x) { return static_cast<std::int32_t>(x.value()); }
    Vec random_vector() override {
        // half: both uniform over the port's range; a quarter: r within +-2 of thr (wrapping
        // at the ends of the range) so that equality is hit; a quarter: extreme values
        const int w = f_.resp_w;
        const long mode = rng_.in_range(0, 3);
        if (mode <= 1) return {rng_.any_signed(w), rng_.any_signed(w)};
        if (mode == 2) {
            const Word thr = rng_.any_signed(w);
            return {Word::sgn(thr.value() + rng_.in_range(-2, 2), w), thr};
        }
        return {Word::sgn(rng_.pick(edges_), w), Word::sgn(rng_.pick(edges_), w)};
    }
};

// ---- local_maximum: combinational -------------------------------------------------------

/// in = r11 .. r33; corner after the inputs settle (no clock, no hold checks).
class LocalMaximumBench final : public VectorBench {
public:
    LocalMaximumBench(const Formats& f, long random, std::uint64_t seed) : VectorBench(f, random, seed) {
        const int w = f.resp_w;
        std::vector<Vec> e;
        // two-level windows: every tie pattern of the centre with its neighbours
        for (const auto& [lo, hi] : level_pairs(w)) add_two_level_windows(e, Word::sgn(lo, w), Word::sgn(hi, w));
        set_extremes(std::move(e));
        expected_.out = {Word::uns(0, 1)};
    }
    const char* name() const override { return "local_maximum"; }
    int out_width() const override { return 1; }
    int widest_input() const override { return f_.resp_w; }
    std::vector<std::string> output_names() const override { return {"corner"}; }
    std::string describe(const Vec& v) const override { return "r=" + matrix_text(v, 0); }

    bool next(std::vector<std::int32_t>& in) override {
        Vec v;
        long index;
        if (!take(v, index)) return false;
        expected_ = {{Word::uns(local_maximum(matrix3(v)) ? 1 : 0, 1)}, index, v};
        completes_ = true;
        in.clear();
        for (const Word& x : v) in.push_back(static_cast<std::int32_t>(x.value()));
        ++cycle_;
        return true;
    }

private:
    Vec random_vector() override {
        // a third uniform over the port's range (a corner in 1 of 9); a third from -2..2
        // (ties everywhere); a third uniform with the centre at the neighbours' maximum
        // -1, +0 or +1 (wrapping), where the strict comparison decides
        const int w = f_.resp_w;
        const long mode = rng_.in_range(0, 2);
        Vec v;
        for (int k = 0; k < 9; ++k)
            v.push_back(mode == 1 ? Word::sgn(rng_.in_range(-2, 2), w) : rng_.any_signed(w));
        if (mode == 2) {
            std::int64_t mx = v[0].value();
            for (int k = 0; k < 9; ++k)
                if (k != 4) mx = std::max(mx, v[k].value());
            v[4] = Word::sgn(mx + rng_.in_range(-1, 1), w);
        }
        return v;
    }
};

}  // namespace

std::vector<std::int64_t> signed_edges(int width, const std::vector<std::int64_t>& extra) {
    const std::int64_t mn = Word::most_negative(width).value(), mx = -(mn + 1);
    std::vector<std::int64_t> e = {mn, mn + 1, -1, 0, 1, mx - 1, mx};
    for (std::int64_t x : extra)
        if (x >= mn && x <= mx) e.push_back(x);
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    return e;
}

std::unique_ptr<Bench> make_bench(int id, const Formats& f, long random, std::uint64_t seed) {
    switch (id) {
        case STAGE_SOBEL_X: return std::make_unique<SobelBench>(false, f, random, seed);
        case STAGE_SOBEL_Y: return std::make_unique<SobelBench>(true, f, random, seed);
        case STAGE_M_PRODUCTS: return std::make_unique<MProductsBench>(f, random, seed);
        case STAGE_BLOCK_FILTER: return std::make_unique<BlockFilterBench>(f, random, seed);
        case STAGE_HARRIS_RESPONSE: return std::make_unique<HarrisResponseBench>(f, random, seed);
        case STAGE_THRESHOLD: return std::make_unique<ThresholdBench>(f, random, seed);
        case STAGE_LOCAL_MAXIMUM: return std::make_unique<LocalMaximumBench>(f, random, seed);
        default: throw std::invalid_argument("unknown entity id " + std::to_string(id));
    }
}

}  // namespace hc::stage
