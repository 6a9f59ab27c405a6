// spec_model_test.cpp: the lean word against Word, and the spec model against the cycle model.
#include <catch2/catch.hpp>

#include <cstdint>
#include <limits>
#include <random>
#include <utility>

#include "model/driver/host_driver.hpp"
#include "model/fixed/word.hpp"
#include "model/fixed/lean_word.hpp"
#include "model/harris/block_filter.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/spec/spec_model.hpp"

using namespace hc;

namespace {

// Values of a given width: the extremes and their neighbours, then random ones.
std::vector<std::int64_t> values(int w, bool s, std::mt19937_64& rng, int n_random) {
    const std::int64_t lo = s ? -(std::int64_t{1} << (w - 1)) : 0;
    const std::int64_t hi = s ? (std::int64_t{1} << (w - 1)) - 1 : (std::int64_t{1} << w) - 1;
    std::vector<std::int64_t> v{lo, lo + 1, hi, hi - 1, 0, 1};
    if (s) v.push_back(-1);
    std::uniform_int_distribution<std::int64_t> d(lo, hi);
    for (int k = 0; k < n_random; ++k) v.push_back(d(rng));
    for (auto& x : v) x = std::clamp(x, lo, hi);
    return v;
}

template <class L>
void check_same(const Word& w, const L& l, const char* op) {
    INFO(op << ": Word " << w.value() << " (" << w.width() << " bits) vs lean " << l.value() << " ("
            << l.width() << " bits)");
    REQUIRE(l.value() == w.value());
    REQUIRE(l.width() == w.width());
    REQUIRE(l.is_signed() == w.is_signed());
}

template <class L>
void lean_equals_word(int max_w) {
    std::mt19937_64 rng(20150101);
    for (int wa = 2; wa <= max_w; wa += (wa < 12 ? 1 : 5))
        for (int wb : {2, 3, 8, wa}) {
            if (wb > max_w) continue;
            for (bool s : {true, false}) {
                // a lean word holds unsigned values below 2^(rep_bits-1) only (documented)
                if (!s && (wa >= L::rep_bits || wb >= L::rep_bits)) continue;
                for (std::int64_t a : values(wa, s, rng, 6))
                    for (std::int64_t b : values(wb, s, rng, 3)) {
                        const Word A = Word::make(a, wa, s), B = Word::make(b, wb, s);
                        const L la = L::make(a, wa, s), lb = L::make(b, wb, s);
                        check_same(A, la, "make");
                        check_same(A + B, la + lb, "+");
                        check_same(A - B, la - lb, "-");
                        if (wa + wb <= std::min(L::rep_bits, Word::max_width)) check_same(A * B, la * lb, "*");
                        if (s) check_same(-A, -la, "unary -");
                        check_same(as_signed(A), as_signed(la), "as_signed");
                        for (int n : {1, 2, wa - 1, wa, wa + 1, max_w})
                            if (n >= 1 && n <= max_w && (s || n < L::rep_bits)) check_same(resize(A, n), resize(la, n), "resize");
                        for (int hi : {wa - 1, wa / 2})
                            for (int lo : {0, hi / 2, hi})
                                if (lo <= hi && hi >= 0) check_same(slice(A, hi, lo), slice(la, hi, lo), "slice");
                        CHECK((A < B) == (la < lb));
                        CHECK((A >= B) == (la >= lb));
                        CHECK(A.bits() == la.bits());
                    }
            }
        }
}

}  // namespace

TEST_CASE("the 32-bit lean word computes what Word computes on random and extreme values", "[model][spec]") {
    lean_equals_word<Lean32>(32);
}

TEST_CASE("the 64-bit lean word computes what Word computes on random and extreme values", "[model][spec]") {
    lean_equals_word<Lean64>(62);
}

TEST_CASE("the most negative lean word is the hardware's find-max reset value", "[model][spec]") {
    CHECK(Lean64::most_negative(32).value() == Word::most_negative(32).value());
    CHECK(Lean32::most_negative(32).value() == -2147483648LL);
}

TEST_CASE("the spec model's first frame uses the find-max reset value as its maximum", "[model][spec]") {
    const spec::SpecModel m;
    const Image a = make_pattern(Pattern::blocks, 64, 36, 0), b = make_pattern(Pattern::blocks, 64, 36, 1);
    std::int64_t prev = m.reset_max();
    const auto out = m.run({&a, &b}, prev, 1);
    REQUIRE(out.size() == 2);
    CHECK(out[0].thr == m.threshold_for(-(std::int64_t{1} << 31)));
    CHECK(out[0].thr < 0);
    CHECK(out[1].thr == m.threshold_for(out[0].max));
    CHECK(prev == out[1].max);
}

// The window-border responses (whole-frame passes with the block filter taken by column
// sums, model/spec/spec_model.cpp) against the stage functions applied pixel by pixel in
// the run-time-checked Word, block_filter on the 3x3 included: every pixel of three sizes
// (down to 8x8: 2x2 candidate centres), and the maximum.
TEST_CASE("the spec model's responses equal the stage functions in Word at every pixel", "[model][spec]") {
    const Formats f{};
    for (auto [w, h] : {std::pair{61, 41}, std::pair{37, 23}, std::pair{8, 8}}) {
        const Image im = make_pattern(Pattern::random, w, h, 3, 11);
        spec::Response r;
        spec::SpecModel{}.response(im, r);
        REQUIRE(r.width == w);
        REQUIRE(r.height == h);
        auto m_at = [&](int y, int x) {   // M products of the 3x3 neighbourhood centred at (x, y)
            Pixels3 nb;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) nb[i][j] = im.at(y + i - 1, x + j - 1);
            return m_products(sobel_x<Word>(nb, f), sobel_y<Word>(nb, f), f);
        };
        std::int64_t mx = std::numeric_limits<std::int64_t>::min();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                std::int64_t want = 0;   // the window border leaves 0 where nothing is computed
                if (x >= 2 && y >= 2 && x < w - 2 && y < h - 2) {
                    std::array<std::array<Word, 3>, 3> na, nb, nc;
                    for (int i = 0; i < 3; ++i)
                        for (int j = 0; j < 3; ++j) {
                            const auto m = m_at(y + i - 1, x + j - 1);
                            na[i][j] = m.a;
                            nb[i][j] = m.b;
                            nc[i][j] = m.c;
                        }
                    const auto t = harris_response_terms(block_filter(na, f), block_filter(nb, f),
                                                         block_filter(nc, f), f);
                    want = harris_response(t, f).value();
                    if (x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1) mx = std::max(mx, want);
                }
                INFO(w << "x" << h << " x=" << x << " y=" << y);
                REQUIRE(r.at(y, x) == want);
            }
        CHECK(r.x0 == 3);
        CHECK(r.x1 == w - 3);
        CHECK(r.y0 == 3);
        CHECK(r.y1 == h - 3);
        CHECK(r.max == mx);
    }
}

TEST_CASE("the twins regression stream ties local maxima with their neighbours along every axis", "[model][spec]") {
    // each blob is symmetric under a half turn about the midpoint of its two twin pixels, so
    // the twins' responses are equal; the blobs take the four axes in turn. The stream of
    // golden/regression-set.txt: four 40x30 frames.
    const spec::SpecModel m;
    const int axes[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
    int tied[4] = {0, 0, 0, 0};   // twin pairs above the threshold and above their other neighbours
    for (int frame = 0; frame < 4; ++frame) {
        const Image img = make_pattern(Pattern::twins, 40, 30, frame);
        spec::Response r;
        m.response(img, r);
        const std::int64_t thr = m.threshold_for(r.max);
        for (int y = r.y0 + 1; y + 1 < r.y1; ++y)
            for (int x = r.x0 + 1; x + 1 < r.x1; ++x) {
                const std::int64_t c = r.at(y, x);
                if (c <= 0 || c < thr) continue;
                for (int a = 0; a < 4; ++a) {
                    const int tx = x + axes[a][0], ty = y + axes[a][1];
                    if (r.at(ty, tx) != c) continue;
                    bool peak = true;   // above every other neighbour of both twins
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            if ((dx || dy) && !(x + dx == tx && y + dy == ty)) peak = peak && r.at(y + dy, x + dx) < c;
                            if ((dx || dy) && !(tx + dx == x && ty + dy == y)) peak = peak && r.at(ty + dy, tx + dx) < c;
                        }
                    if (peak) ++tied[a];
                }
            }
    }
    for (int a = 0; a < 4; ++a) {
        INFO("axis (" << axes[a][0] << ", " << axes[a][1] << ")");
        CHECK(tied[a] >= 2);
    }
}
