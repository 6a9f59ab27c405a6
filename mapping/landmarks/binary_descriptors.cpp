// Purpose: BRIEF (Calonder et al. 2010) and FREAK (Alahi et al. 2012) as cv::Feature2D
// descriptors, written from the papers (Debian's OpenCV has no xfeatures2d). Both read a
// grey 8-bit image padded by reflection, so the `pad` border policy and the `drop` policy
// produce identical descriptors for keypoints whose pattern lies inside the image.
// docs/landmarks.md ("BRIEF and FREAK") lists where they may differ from the authors'.
#include "mapping/landmarks/descriptors.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace hc::landmarks {
namespace {

/// Grey 8-bit copy of `image` (1 or 3/4 channels, CV_8U) for a descriptor that describes
/// given keypoints; InputError otherwise, or when asked to detect keypoints.
cv::Mat descriptor_input(cv::InputArray image, bool useProvidedKeypoints, const char* who) {
    if (!useProvidedKeypoints)
        throw InputError(std::string(who) + ": a descriptor only (call compute with keypoints)");
    const cv::Mat m = image.getMat();
    if (m.empty()) throw InputError(std::string(who) + ": empty image");
    if (m.depth() != CV_8U)
        throw InputError(std::string(who) + ": image must be 8-bit, got " + cv::typeToString(m.type()));
    if (m.channels() == 1) return m;
    cv::Mat g;
    if (m.channels() == 3) cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
    else if (m.channels() == 4) cv::cvtColor(m, g, cv::COLOR_BGRA2GRAY);
    else throw InputError(std::string(who) + ": image must have 1, 3 or 4 channels");
    return g;
}

/// The keypoint's pixel: coordinates rounded to nearest (integer shifts of the image shift
/// it by the same integers).
cv::Point pixel_of(const cv::KeyPoint& k) { return {cvRound(k.pt.x), cvRound(k.pt.y)}; }

/// Keypoints whose pixel lies `margin` pixels or more inside the image; the rest are removed
/// (`drop`) or kept (`pad`). Keypoints with non-finite coordinates are always removed.
void apply_border(std::vector<cv::KeyPoint>& kps, cv::Size size, int margin, BorderPolicy b) {
    std::erase_if(kps, [&](const cv::KeyPoint& k) {
        if (!std::isfinite(k.pt.x) || !std::isfinite(k.pt.y)) return true;
        if (b == BorderPolicy::pad)
            return std::fabs(k.pt.x) > 1e6f || std::fabs(k.pt.y) > 1e6f;
        const cv::Point p = pixel_of(k);
        return p.x < margin || p.y < margin || p.x >= size.width - margin ||
               p.y >= size.height - margin;
    });
}

/// `grey` padded by `margin` pixels on each side (BORDER_REFLECT_101); pixel (x, y) of the
/// image is pixel (x + margin, y + margin) of the result. Keypoints of the `pad` policy
/// farther out than the margin are clamped onto the padded image.
cv::Mat padded(const cv::Mat& grey, int margin) {
    cv::Mat p;
    cv::copyMakeBorder(grey, p, margin, margin, margin, margin, cv::BORDER_REFLECT_101);
    return p;
}

cv::Point clamp_into(cv::Point p, cv::Size s) {
    return {std::clamp(p.x, 0, s.width - 1), std::clamp(p.y, 0, s.height - 1)};
}

// ---- BRIEF --------------------------------------------------------------------------------

constexpr int brief_bits = 256;
constexpr int brief_kernel = BriefDescriptor::kernel_size;  // 9 (Calonder et al. 2010, section 3.1)
constexpr double brief_sigma = 2.0;  // the Gaussian's sigma (same section)

/// SplitMix64 (Steele, Lea, Flood 2014): a fixed, platform-independent 64-bit sequence.
struct SplitMix64 {
    std::uint64_t s;
    std::uint64_t next() {
        std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    /// Standard normal approximated by the Irwin-Hall sum of 12 uniforms minus 6: only
    /// exact double additions, so the pattern is the same on every platform.
    double normal() {
        double sum = 0;
        for (int k = 0; k < 12; ++k) sum += double(next() >> 32) / 4294967296.0;
        return sum - 6.0;
    }
};

std::vector<cv::Vec4i> make_brief_pattern() {
    const int half = BriefDescriptor::patch_size / 2;
    const double sigma = BriefDescriptor::patch_size / 5.0;  // G II: sigma^2 = S^2 / 25
    SplitMix64 rng{0x42524945465f4849ULL};
    auto coord = [&] {
        const long v = std::lround(rng.normal() * sigma);
        return static_cast<int>(std::clamp<long>(v, -half, half - 1));  // inside the S x S patch
    };
    std::vector<cv::Vec4i> p(brief_bits);
    for (auto& t : p) {
        do {
            t = cv::Vec4i(coord(), coord(), coord(), coord());
        } while (t[0] == t[2] && t[1] == t[3]);  // a point tested against itself says nothing
    }
    return p;
}

// ---- FREAK --------------------------------------------------------------------------------

constexpr int freak_rings = 7;
constexpr int freak_per_ring = 6;
constexpr int freak_fields = freak_rings * freak_per_ring + 1;  // 43
constexpr int freak_pairs = 512;

/// Ring radii in units of the pattern's reach: outer ring 2/3 with sigma 1/3 (reach 1),
/// each inner ring 0.7 times the previous; sigma = radius / 2; the centre field takes the
/// innermost ring's sigma. Odd rings are turned by half a field (pi / 6), so neighbouring
/// rings interleave as in the paper's Figure 4.
std::vector<FreakDescriptor::Field> make_freak_fields() {
    std::vector<FreakDescriptor::Field> f;
    double r = 2.0 / 3.0;
    for (int ring = 0; ring < freak_rings; ++ring, r *= 0.7) {
        const double turn = (ring % 2) ? CV_PI / freak_per_ring : 0.0;
        for (int k = 0; k < freak_per_ring; ++k) {
            const double a = turn + 2 * CV_PI * k / freak_per_ring;
            f.push_back({float(r * std::cos(a)), float(r * std::sin(a)), float(r / 2)});
        }
    }
    f.push_back({0.f, 0.f, f.back().sigma});
    return f;
}

/// 512 of the 903 field pairs, coarse to fine: by the sum of the two sigmas, descending,
/// then by indices. (The authors learn their pairs from data; theirs also run coarse to fine.)
std::vector<cv::Vec2i> make_freak_pairs() {
    const auto& f = FreakDescriptor::fields();
    std::vector<cv::Vec2i> all;
    for (int a = 0; a < freak_fields; ++a)
        for (int b = a + 1; b < freak_fields; ++b) all.emplace_back(a, b);
    std::stable_sort(all.begin(), all.end(), [&](const cv::Vec2i& p, const cv::Vec2i& q) {
        return f[p[0]].sigma + f[p[1]].sigma > f[q[0]].sigma + f[q[1]].sigma;
    });
    all.resize(freak_pairs);
    return all;
}

/// Orientation pairs: every pair of fields on the same ring (15 per ring, 105 in all).
std::vector<cv::Vec2i> make_orientation_pairs() {
    std::vector<cv::Vec2i> p;
    for (int ring = 0; ring < freak_rings; ++ring)
        for (int a = 0; a < freak_per_ring; ++a)
            for (int b = a + 1; b < freak_per_ring; ++b)
                p.emplace_back(ring * freak_per_ring + a, ring * freak_per_ring + b);
    return p;
}

/// Mean intensity over the (2 s + 1)^2 box centred on c, from an integral image.
float box_mean(const cv::Mat& integral, cv::Point c, int s) {
    const int x0 = c.x - s, y0 = c.y - s, x1 = c.x + s + 1, y1 = c.y + s + 1;
    const int sum = integral.at<int>(y1, x1) - integral.at<int>(y0, x1) -
                    integral.at<int>(y1, x0) + integral.at<int>(y0, x0);
    return float(sum) / float((2 * s + 1) * (2 * s + 1));
}

}  // namespace

// ---- BriefDescriptor ----------------------------------------------------------------------

cv::Ptr<BriefDescriptor> BriefDescriptor::create(BorderPolicy border, BriefSmoothing smoothing) {
    return cv::makePtr<BriefDescriptor>(border, smoothing);
}
BriefDescriptor::BriefDescriptor(BorderPolicy border, BriefSmoothing smoothing)
    : border_(border), smoothing_(smoothing) {}

const std::vector<cv::Vec4i>& BriefDescriptor::pattern() {
    static const std::vector<cv::Vec4i> p = make_brief_pattern();
    return p;
}

namespace {

/// The 256 tests of every keypoint: `value(centre, offset)` is the smoothed intensity at
/// `offset` (in the memory of the image `centre` points into) from the keypoint's pixel.
template <class T, class Value>
cv::Mat brief_tests(const cv::Mat& img, int margin, const std::vector<cv::KeyPoint>& keypoints, Value value) {
    const auto& pat = BriefDescriptor::pattern();
    const auto step = static_cast<std::ptrdiff_t>(img.step1());
    std::vector<std::ptrdiff_t> off_a(brief_bits), off_b(brief_bits);
    for (size_t k = 0; k < brief_bits; ++k) {
        off_a[k] = pat[k][1] * step + pat[k][0];
        off_b[k] = pat[k][3] * step + pat[k][2];
    }
    cv::Mat d(static_cast<int>(keypoints.size()), brief_bits / 8, CV_8U);
    const int half = BriefDescriptor::patch_size / 2;
    const cv::Size inner(img.cols - 2 * half, img.rows - 2 * half);
    for (size_t i = 0; i < keypoints.size(); ++i) {
        // the centre, clamped so that the whole patch stays on the padded image
        cv::Point c = pixel_of(keypoints[i]) + cv::Point(margin, margin);
        c = clamp_into(c - cv::Point(half, half), inner) + cv::Point(half, half);
        const T* centre = img.ptr<T>(c.y) + c.x;
        uchar* row = d.ptr<uchar>(static_cast<int>(i));
        for (size_t byte = 0; byte < brief_bits / 8; ++byte) {
            unsigned v = 0;
            for (size_t bit = 0; bit < 8; ++bit) {
                const size_t k = 8 * byte + bit;
                v |= static_cast<unsigned>(value(centre, off_a[k]) < value(centre, off_b[k])) << bit;
            }
            row[byte] = static_cast<uchar>(v);
        }
    }
    return d;
}

}  // namespace

void BriefDescriptor::detectAndCompute(cv::InputArray image, cv::InputArray,
                                       std::vector<cv::KeyPoint>& keypoints,
                                       cv::OutputArray descriptors, bool useProvidedKeypoints) {
    const cv::Mat grey = descriptor_input(image, useProvidedKeypoints, "BRIEF");
    // the patch reaches S/2 pixels left/up and S/2 - 1 right/down, the kernel K/2 more
    const int margin = patch_size / 2 + brief_kernel / 2;
    apply_border(keypoints, grey.size(), margin, border_);
    if (smoothing_ == BriefSmoothing::gaussian) {
        cv::Mat smooth;
        cv::GaussianBlur(padded(grey, margin), smooth, cv::Size(brief_kernel, brief_kernel),
                         brief_sigma, brief_sigma, cv::BORDER_REFLECT_101);
        brief_tests<uchar>(smooth, margin, keypoints,
                           [](const uchar* c, std::ptrdiff_t o) { return int(c[o]); })
            .copyTo(descriptors);
        return;
    }
    // box: integral image of the padded image; entry (y, x) sums pixels [0, y) x [0, x), so
    // the 9 x 9 box centred on padded pixel (y, x) is read at rows/columns y - 4 and y + 5
    cv::Mat integral;
    cv::integral(padded(grey, margin), integral, CV_32S);
    const auto istep = static_cast<std::ptrdiff_t>(integral.step1());
    const int k = brief_kernel / 2;
    const std::ptrdiff_t tl = -k * istep - k, tr = -k * istep + k + 1, bl = (k + 1) * istep - k,
                         br = (k + 1) * istep + k + 1;
    brief_tests<int>(integral, margin, keypoints, [&](const int* c, std::ptrdiff_t o) {
        const int* p = c + o;   // modulo 2^32: exact for any box sum even if the integral wraps
        return static_cast<int>(unsigned(p[br]) - unsigned(p[tr]) - unsigned(p[bl]) + unsigned(p[tl]));
    }).copyTo(descriptors);
}

int BriefDescriptor::descriptorSize() const { return brief_bits / 8; }
cv::String BriefDescriptor::getDefaultName() const { return "hc.features.BriefDescriptor"; }

// ---- FreakDescriptor ----------------------------------------------------------------------

cv::Ptr<FreakDescriptor> FreakDescriptor::create(bool orientation, float pattern_scale,
                                                 BorderPolicy border) {
    return cv::makePtr<FreakDescriptor>(orientation, pattern_scale, border);
}

FreakDescriptor::FreakDescriptor(bool orientation, float pattern_scale, BorderPolicy border)
    : orientation_(orientation), scale_(pattern_scale), border_(border) {
    if (!(pattern_scale >= 4.f && pattern_scale <= 256.f))
        throw InputError("FREAK: pattern_scale = " + std::to_string(pattern_scale) +
                         " is out of range [4, 256] pixels");
}

const std::vector<FreakDescriptor::Field>& FreakDescriptor::fields() {
    static const std::vector<Field> f = make_freak_fields();
    return f;
}

const std::vector<cv::Vec2i>& FreakDescriptor::pairs() {
    static const std::vector<cv::Vec2i> p = make_freak_pairs();
    return p;
}

void FreakDescriptor::detectAndCompute(cv::InputArray image, cv::InputArray,
                                       std::vector<cv::KeyPoint>& keypoints,
                                       cv::OutputArray descriptors, bool useProvidedKeypoints) {
    const cv::Mat grey = descriptor_input(image, useProvidedKeypoints, "FREAK");
    const auto& f = fields();
    const auto& pr = pairs();
    static const std::vector<cv::Vec2i> orient = make_orientation_pairs();
    // a field centre is at most `scale_ * radius` away (rounded), its box half side
    // round(scale_ * sigma): reach <= scale_ + 1; one more pixel for the integral image
    const int margin = static_cast<int>(std::ceil(scale_)) + 2;
    apply_border(keypoints, grey.size(), margin, border_);
    cv::Mat integral;
    cv::integral(padded(grey, margin), integral, CV_32S);
    std::vector<int> half(f.size());
    for (size_t k = 0; k < f.size(); ++k) half[k] = std::max(0, cvRound(scale_ * f[k].sigma));
    const cv::Size inner(integral.cols - 1 - 2 * margin, integral.rows - 1 - 2 * margin);

    cv::Mat d = cv::Mat::zeros(static_cast<int>(keypoints.size()), freak_pairs / 8, CV_8U);
    std::vector<float> mean(f.size());
    std::vector<cv::Point> at(f.size());
    for (size_t i = 0; i < keypoints.size(); ++i) {
        const cv::Point c =
            clamp_into(pixel_of(keypoints[i]), inner) + cv::Point(margin, margin);
        double cs = 1, sn = 0;
        if (orientation_) {
            for (size_t k = 0; k < f.size(); ++k) {
                at[k] = c + cv::Point(cvRound(scale_ * f[k].x), cvRound(scale_ * f[k].y));
                mean[k] = box_mean(integral, at[k], half[k]);
            }
            // mean local gradient (Alahi et al. 2012, eq. 3) over same-ring field pairs
            double gx = 0, gy = 0;
            for (const auto& p : orient) {
                const double dx = f[p[0]].x - f[p[1]].x, dy = f[p[0]].y - f[p[1]].y;
                const double n = std::hypot(dx, dy);
                const double di = mean[p[0]] - mean[p[1]];
                gx += di * dx / n;
                gy += di * dy / n;
            }
            const double angle = std::atan2(gy, gx);
            cs = std::cos(angle);
            sn = std::sin(angle);
            float deg = static_cast<float>(angle * 180.0 / CV_PI);
            keypoints[i].angle = deg < 0 ? deg + 360.f : deg;
        }
        for (size_t k = 0; k < f.size(); ++k) {
            const double x = f[k].x * cs - f[k].y * sn, y = f[k].x * sn + f[k].y * cs;
            at[k] = c + cv::Point(cvRound(scale_ * x), cvRound(scale_ * y));
            mean[k] = box_mean(integral, at[k], half[k]);
        }
        uchar* row = d.ptr<uchar>(static_cast<int>(i));
        for (int k = 0; k < freak_pairs; ++k) {
            const cv::Vec2i& p = pr[static_cast<size_t>(k)];
            if (mean[static_cast<size_t>(p[0])] > mean[static_cast<size_t>(p[1])])
                row[k >> 3] = static_cast<uchar>(row[k >> 3] | (1 << (k & 7)));
        }
    }
    d.copyTo(descriptors);
}

int FreakDescriptor::descriptorSize() const { return freak_pairs / 8; }
cv::String FreakDescriptor::getDefaultName() const { return "hc.features.FreakDescriptor"; }

}  // namespace hc::landmarks
