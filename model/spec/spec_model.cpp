// spec_model.cpp: see spec_model.hpp. Three passes per frame, each calling the shared
// stage functions once per pixel:
//   1. sobel_x, sobel_y, m_products        image (w0 x h0) -> A, B, C planes (w0-2 x h0-2)
//   2. block_filter x3, harris_response    A, B, C (w1 x h1) -> R plane (w1-2 x h1-2)
//   3. threshold x9, local_maximum         R -> corner mask
// Each pass is "valid" (output shrinks by 2 per axis). Border::window runs them on the
// image as is; Border::reflect101 pads each pass's input by one pixel the way OpenCV's
// BORDER_REFLECT_101 does (at the Sobel and again at the block sum), so every pixel gets
// a response, and pads R with the most negative value for the NMS (OpenCV's dilate ignores
// pixels outside the image).
//
// Speed: the Formats of the thesis (and the untruncated ablation) are compile-time
// constants here, so every width in the LeanWord operations folds and the inner loops
// vectorise; other formats run the same code with runtime widths in 64-bit words.
#include "model/spec/spec_model.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "model/harris/block_filter.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/local_maximum.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/harris/threshold.hpp"
#include "model/fixed/lean_word.hpp"

namespace hc::spec {

namespace {

constexpr Formats kThesis{};

constexpr Formats make_untruncated() {
    Formats f;
    f.m_prod_w = 21;   // +-1020^2 = 1,040,400 < 2^20: 21 signed bits hold every product
    f.m_drop = 0;      // keep all 21 bits (hardware: floor(/32))
    f.bf_sum_w = 25;   // 9 * 1,040,400 = 9,363,600 < 2^24: 25 signed bits
    f.bf_drop = 0;     // keep all 25 bits (hardware: floor(/16))
    f.ktr_w = 46;      // (A+C)^2 < 2^49, times (1/32 + 1/128) < 2^44: 46 bits spare
    f.resp_w = 50;     // AC < 2^47, so |R| < 2^48: 50 bits
    return f;
}
constexpr Formats kUntruncated = make_untruncated();

// Formats known at compile time (S) or at run time (D); get() is all a kernel asks.
template <const Formats& F>
struct StaticFormats {
    static constexpr const Formats& get() { return F; }
};
struct DynamicFormats {
    const Formats* f;
    const Formats& get() const { return *f; }
};

// The storage word of passes 1 and 2: 32 bits when every width there fits.
constexpr bool fits32(const Formats& f) {
    return 2 * f.sobel_w <= 32 && f.m_prod_w <= 32 && f.bf_sum_w <= 32;
}

/// Pass 1: Sobel and M products at every pixel whose 3x3 neighbourhood is in `src`.
template <class T, class FS>
void m_pass(const FS fs, const std::uint8_t* src, int w0, int h0, std::int32_t* A, std::int32_t* B,
            std::int32_t* C) {
    const Formats& f = fs.get();
    const int w = w0 - 2, h = h0 - 2;
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* r0 = src + static_cast<size_t>(y) * w0;
        const std::uint8_t* r1 = r0 + w0;
        const std::uint8_t* r2 = r1 + w0;
        std::int32_t* a = A + static_cast<size_t>(y) * w;
        std::int32_t* b = B + static_cast<size_t>(y) * w;
        std::int32_t* c = C + static_cast<size_t>(y) * w;
#pragma GCC ivdep
        for (int x = 0; x < w; ++x) {
            const Pixels3 nb{{{r0[x], r0[x + 1], r0[x + 2]},
                              {r1[x], r1[x + 1], r1[x + 2]},
                              {r2[x], r2[x + 1], r2[x + 2]}}};
            const T ix = sobel_x<T>(nb, f);
            const T iy = sobel_y<T>(nb, f);
            const MProductsT<T> m = m_products(ix, iy, f);
            a[x] = static_cast<std::int32_t>(m.a.v);   // m_w <= 32 bits (fits32 / validate)
            b[x] = static_cast<std::int32_t>(m.b.v);
            c[x] = static_cast<std::int32_t>(m.c.v);
        }
    }
}

/// Pass 2: block sums and the response at every pixel whose 3x3 neighbourhood is in the
/// M planes (w1 x h1). The block filter is taken in its two shared halves: each row's
/// column sums first (block_column_sum, into `cols`: 3 x w1 words), then each window adds
/// three of them (block_filter_of_columns), so every column sum serves three windows.
/// Column sums are bf_sum_w-bit words (up to 40 bits): stored in T's representation.
template <class T>
using Rep = decltype(T{}.v);

template <class T, bool ExactK, class FS>
void response_pass(const FS fs, const std::int32_t* A, const std::int32_t* B, const std::int32_t* C,
                   int w1, int h1, std::int64_t* R, int r_stride, Rep<T>* cols) {
    const Formats& f = fs.get();
    const int mw = f.m_w(), sw = f.bf_sum_w;
    const int w = w1 - 2, h = h1 - 2;
    Rep<T>* ca = cols;
    Rep<T>* cb = cols + w1;
    Rep<T>* cc = cols + 2 * static_cast<size_t>(w1);
    for (int y = 0; y < h; ++y) {
        const size_t o0 = static_cast<size_t>(y) * w1, o1 = o0 + w1, o2 = o1 + w1;
        // the M registers are m_w-bit signed words, the column sums bf_sum_w-bit ones
#pragma GCC ivdep
        for (int x = 0; x < w1; ++x) {
            ca[x] = block_column_sum(T{A[o0 + x], mw, true}, T{A[o1 + x], mw, true}, T{A[o2 + x], mw, true}, f).v;
            cb[x] = block_column_sum(T{B[o0 + x], mw, true}, T{B[o1 + x], mw, true}, T{B[o2 + x], mw, true}, f).v;
            cc[x] = block_column_sum(T{C[o0 + x], mw, true}, T{C[o1 + x], mw, true}, T{C[o2 + x], mw, true}, f).v;
        }
        std::int64_t* r = R + static_cast<size_t>(y) * r_stride;
#pragma GCC ivdep
        for (int x = 0; x < w; ++x) {
            const T ba = block_filter_of_columns(T{ca[x], sw, true}, T{ca[x + 1], sw, true}, T{ca[x + 2], sw, true}, f);
            const T bb = block_filter_of_columns(T{cb[x], sw, true}, T{cb[x + 1], sw, true}, T{cb[x + 2], sw, true}, f);
            const T bc = block_filter_of_columns(T{cc[x], sw, true}, T{cc[x + 1], sw, true}, T{cc[x + 2], sw, true}, f);
            // the response needs 2*(bf_w+1) bits: continue in 64-bit words
            const Lean64 a{ba.v, ba.w, true}, b{bb.v, bb.w, true}, c{bc.v, bc.w, true};
            const ResponseTermsT<Lean64> t = harris_response_terms(a, b, c, f);
            if constexpr (ExactK) {
                // k = 0.04 = 1/25 exactly: 25*R = 25*(AC - B^2) - (A+C)^2, no rounding at all
                const std::int64_t tr = a.v + c.v;
                r[x] = 25 * (t.ac.v - t.bb.v) - tr * tr;
            } else {
                r[x] = harris_response(t, f).v;
            }
        }
    }
}

/// `src` (w x h) padded by one pixel on every side with BORDER_REFLECT_101 (..2 1 |0 1 2..).
template <class V>
void pad_reflect101(const V* src, int w, int h, std::vector<V>& dst) {
    const int pw = w + 2;
    dst.resize(static_cast<size_t>(pw) * (h + 2));
    auto refl = [](int i, int n) { return n == 1 ? 0 : (i < 0 ? -i : (i >= n ? 2 * n - 2 - i : i)); };
    for (int y = -1; y <= h; ++y) {
        const V* s = src + static_cast<size_t>(refl(y, h)) * w;
        V* d = dst.data() + static_cast<size_t>(y + 1) * pw;
        d[0] = s[refl(-1, w)];
        std::copy_n(s, w, d + 1);
        d[pw - 1] = s[refl(w, w)];
    }
}

struct Workspace {
    std::vector<std::uint8_t> img;
    std::vector<std::int32_t> a, b, c, pa, pb, pc, cols32;
    std::vector<std::int64_t> cols64;
    template <class R>
    R* cols(size_t n) {
        if constexpr (sizeof(R) == 4) return (cols32.resize(n), cols32.data());
        else return (cols64.resize(n), cols64.data());
    }
};

template <class T, bool ExactK, class FS>
void compute(const FS fs, const Image& im, Border border, Workspace& ws, Response& out) {
    const int W = im.width, H = im.height;
    out.width = W;
    out.height = H;
    if (out.r.size() != static_cast<size_t>(W) * H || border != Border::window)
        out.r.assign(static_cast<size_t>(W) * H, 0);   // the window border keeps its zeros
    const bool refl = border == Border::reflect101;
    // plane geometry: pass 1 input (w0 x h0) whose (0,0) is image pixel (o0, o0)
    const std::uint8_t* src = im.pixels.data();
    int w0 = W, h0 = H, o0 = 0;
    if (refl) {
        pad_reflect101(im.pixels.data(), W, H, ws.img);
        src = ws.img.data();
        w0 = W + 2;
        h0 = H + 2;
        o0 = -1;
    }
    int w1 = w0 - 2, h1 = h0 - 2, o1 = o0 + 1;
    if (w1 < 3 || h1 < 3) throw std::invalid_argument("spec model: image too small for a response");
    const size_t n1 = static_cast<size_t>(w1) * h1;
    ws.a.resize(n1);
    ws.b.resize(n1);
    ws.c.resize(n1);
    m_pass<T>(fs, src, w0, h0, ws.a.data(), ws.b.data(), ws.c.data());
    const std::int32_t *A = ws.a.data(), *B = ws.b.data(), *C = ws.c.data();
    if (refl) {
        pad_reflect101(ws.a.data(), w1, h1, ws.pa);
        pad_reflect101(ws.b.data(), w1, h1, ws.pb);
        pad_reflect101(ws.c.data(), w1, h1, ws.pc);
        A = ws.pa.data();
        B = ws.pb.data();
        C = ws.pc.data();
        w1 += 2;
        h1 += 2;
        o1 -= 1;
    }
    const int w2 = w1 - 2, h2 = h1 - 2, o2 = o1 + 1;
    // R plane (w2 x h2) lands at image pixel (o2, o2), straight into the output
    response_pass<T, ExactK>(fs, A, B, C, w1, h1, out.r.data() + static_cast<size_t>(o2) * W + o2, W,
                             ws.cols<Rep<T>>(3 * static_cast<size_t>(w1)));
    // candidate centres: all 8 neighbours must have a response (window), or all pixels
    if (refl) {
        out.x0 = 0; out.x1 = W; out.y0 = 0; out.y1 = H;
    } else {
        out.x0 = o2 + 1; out.x1 = o2 + w2 - 1; out.y0 = o2 + 1; out.y1 = o2 + h2 - 1;
    }
    std::int64_t mx = std::numeric_limits<std::int64_t>::min();
    for (int y = out.y0; y < out.y1; ++y) {
        const std::int64_t* row = out.r.data() + static_cast<size_t>(y) * W;
        for (int x = out.x0; x < out.x1; ++x) mx = std::max(mx, row[x]);
    }
    out.max = mx;
}

template <bool ExactK>
void dispatch(const Formats& f, const Image& im, Border border, Workspace& ws, Response& out) {
    if (f == kThesis) return compute<Lean32, ExactK>(StaticFormats<kThesis>{}, im, border, ws, out);
    if (f == kUntruncated) return compute<Lean32, ExactK>(StaticFormats<kUntruncated>{}, im, border, ws, out);
    compute<Lean64, ExactK>(DynamicFormats{&f}, im, border, ws, out);
}

thread_local Workspace tls_ws;

}  // namespace

Formats Options::untruncated() { return kUntruncated; }

std::string Options::describe() const {
    std::ostringstream s;
    s << "k=" << (k == KRule::shifts ? "2^-5+2^-7" : "0.04") << " thr="
      << (thr == ThrRule::shifts ? "(2^-7+2^-9)max" : "0.01max") << " max="
      << (max_from == MaxFrom::previous ? "previous" : "current") << " nms="
      << (nms == Nms::strict ? "strict" : "non-strict") << " border="
      << (border == Border::window ? "window" : "reflect101")
      << (formats == kThesis ? "" : (formats == kUntruncated ? " formats=untruncated" : " formats=custom"));
    return s.str();
}

SpecModel::SpecModel(const Options& o) : o_(o) {
    o_.formats.validate();
    if (o_.formats.m_w() > 32 || o_.formats.bf_w() > 32)
        throw std::invalid_argument("spec model: M and block-sum words wider than 32 bits");
}

void SpecModel::response(const Image& img, Response& out) const {
    if (o_.k == KRule::exact) dispatch<true>(o_.formats, img, o_.border, tls_ws, out);
    else dispatch<false>(o_.formats, img, o_.border, tls_ws, out);
}

std::int64_t SpecModel::reset_max() const { return Word::most_negative(o_.formats.resp_w).value(); }

std::int64_t SpecModel::threshold_for(std::int64_t max) const {
    if (o_.thr == ThrRule::exact) {
        // keep r >= 0.01*max: for integers that is r >= ceil(max / 100)
        const std::int64_t q = max / 100, rem = max % 100;
        return q + (rem > 0 ? 1 : 0);
    }
    Formats f = o_.formats;
    // exact-k responses are not resp_w-bit words: take the threshold slices of a 62-bit one
    if (o_.k == KRule::exact) f.resp_w = 62;
    return threshold_value(Lean64::sgn(max, f.resp_w), f).v;
}

namespace {
struct Uniform {
    static constexpr bool uniform = true;
    std::int64_t t;
    std::int64_t operator()(int, int) const { return t; }
};
struct PerPixel {
    static constexpr bool uniform = false;
    const std::function<std::int64_t(int, int)>* f;
    std::int64_t operator()(int x, int y) const { return (*f)(x, y); }
};

template <class ThrAt>
void nms(const Response& r, const Options& o, ThrAt thr_at, std::vector<std::uint8_t>& mask) {
    const int W = r.width, H = r.height;
    mask.assign(static_cast<size_t>(W) * H, 0);
    const int width = o.k == KRule::exact ? 62 : o.formats.resp_w;
    const std::int64_t outside = std::numeric_limits<std::int64_t>::min() / 2;   // never a maximum
    auto val = [&](int y, int x) -> std::int64_t {
        return (x < 0 || y < 0 || x >= W || y >= H) ? outside : r.at(y, x);
    };
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            if constexpr (ThrAt::uniform) {
                // vectorisable scan: skip 8 centres at once while all are below thr > 0
                const std::int64_t t0 = thr_at(x, y);
                if (t0 > 0) {
                    const std::int64_t* row = r.r.data() + static_cast<size_t>(y) * W;
                    while (x + 8 <= r.x1) {
                        bool any = false;
                        for (int k = 0; k < 8; ++k) any |= row[x + k] >= t0;
                        if (any) break;
                        x += 8;
                    }
                    if (x >= r.x1) break;
                }
            }
            const std::int64_t thr = thr_at(x, y);
            const std::int64_t c = r.at(y, x);
            // shortcut, exact when thr > 0: a centre below thr becomes 0, and 0 is never
            // above (strict) or at least (non-strict, needs c >= thr) neighbours that are
            // 0 or >= thr > 0
            if (c < thr && thr > 0) continue;
            std::array<std::array<Lean64, 3>, 3> t;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    t[i][j] = threshold(Lean64{val(y + i - 1, x + j - 1), width, true},
                                        Lean64{thr, width, true});
            bool corner;
            if (o.nms == Nms::strict) {
                corner = local_maximum(t);
            } else {
                // OpenCV's rule R == dilate(R): at least all 8 neighbours, and above thr
                corner = c >= thr;
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) corner = corner && t[1][1].v >= t[i][j].v;
            }
            if (corner) mask[static_cast<size_t>(y) * W + x] = 1;
        }
}
}  // namespace

void SpecModel::corners(const Response& r, std::int64_t thr, std::vector<std::uint8_t>& mask) const {
    nms(r, o_, Uniform{thr}, mask);
}

void SpecModel::corners(const Response& r, const std::function<std::int64_t(int, int)>& thr_at,
                        std::vector<std::uint8_t>& mask) const {
    nms(r, o_, PerPixel{&thr_at}, mask);
}

long count_corners(const std::vector<std::uint8_t>& mask) {
    long n = 0;
    for (auto v : mask) n += v;
    return n;
}

std::vector<FrameCorners> SpecModel::run(const std::vector<const Image*>& frames, std::int64_t& prev_max,
                                         int threads) const {
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    return run(frames, prev_max, arena);
}

std::vector<FrameCorners> SpecModel::run(const std::vector<const Image*>& frames, std::int64_t& prev_max,
                                         tbb::task_arena& arena) const {
    const int n = static_cast<int>(frames.size());
    std::vector<FrameCorners> out(static_cast<size_t>(n));
    // responses are 8 bytes a pixel: hold as many frames at a time as there are threads (at
    // most 8), not the whole stream; a run allocates these afresh, so each one costs the
    // first touch of its pages in every run
    const int chunk = std::clamp(arena.max_concurrency(), 1, 8);
    std::vector<Response> resp(static_cast<size_t>(std::min(n, chunk)));
    for (int first = 0; first < n; first += chunk) {
        const int last = std::min(n, first + chunk);
        arena.execute([&] {
            tbb::parallel_for(first, last, [&](int k) { response(*frames[k], resp[k - first]); });
        });
        // thresholds follow the stream order: frame k uses frame k-1's maximum
        std::vector<std::int64_t> thr(static_cast<size_t>(last - first));
        for (int k = first; k < last; ++k) {
            const std::int64_t m = resp[k - first].max;
            thr[k - first] = threshold_for(o_.max_from == MaxFrom::previous ? prev_max : m);
            out[k].max = m;
            out[k].thr = thr[k - first];
            prev_max = m;
        }
        arena.execute([&] {
            tbb::parallel_for(first, last, [&](int k) {
                corners(resp[k - first], thr[k - first], out[k].mask);
                out[k].count = count_corners(out[k].mask);
            });
        });
    }
    return out;
}

SpecStream::SpecStream(const Options& o, const Image* before) : m_(o), prev_(m_.reset_max()) {
    if (before && o.max_from == MaxFrom::previous) {
        Response r;
        m_.response(*before, r);
        prev_ = r.max;
    }
}

std::vector<FrameCorners> SpecStream::run(const std::vector<const Image*>& frames, tbb::task_arena& arena) {
    return m_.run(frames, prev_, arena);
}

std::vector<FrameCorners> SpecStream::run(const std::vector<const Image*>& frames, int threads) {
    return m_.run(frames, prev_, threads);
}

}  // namespace hc::spec
