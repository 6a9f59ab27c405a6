// spec_model.hpp: the frame-level ("spec") model of the Harris co-processor: the algorithm
// as the thesis describes it (Schulz 2015, section 5.2), computed for a whole image at once.
//
// Purpose: the same stage functions as the cycle model (model/harris/sobel_x.hpp ...
// local_maximum.hpp), instantiated with LeanWord instead of Word, applied at every pixel:
//   response  R(x,y) at every pixel whose 5x5 gradient neighbourhood lies in the image
//             (Sobel 3x3, M products, 3x3 block sum, R = AC - B^2 - k(A+C)^2);
//   threshold thr = threshold_value(max of the previous frame's R over the window centres);
//   corner    3x3 strict local maximum of the thresholded responses, at every centre
//             whose 7x7 window lies in the image: x in 3..w-4, y in 3..h-4.
// Nothing of the co-processor's stepping is modelled (no quadrants, no load gaps, no
// find-max period): docs/deviations.md lists where the RTL differs and by how much.
//
// Options switch single approximations back to their ideal (the ablation of the eval
// report): k = 0.04, threshold 0.01*max, no LSB dropping in M and the block sum, current
// frame's maximum, non-strict NMS, OpenCV's border (reflect-101 at each filter stage).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"

namespace hc::spec {

enum class Border {
    window,       ///< the thesis: only centres whose 7x7 window lies in the image
    reflect101,   ///< OpenCV's BORDER_DEFAULT at the Sobel and at the block sum; all pixels
};
enum class KRule { shifts, exact };       ///< k = 2^-5 + 2^-7, or k = 0.04 = 1/25
enum class ThrRule { shifts, exact };     ///< thr = max(2^-7 + 2^-9), or 0.01*max
enum class MaxFrom { previous, current }; ///< whose maximum sets a frame's threshold
enum class Nms { strict, non_strict };    ///< centre > all 8 neighbours, or >= all 8

struct Options {
    Formats formats{};
    KRule k = KRule::shifts;
    ThrRule thr = ThrRule::shifts;
    MaxFrom max_from = MaxFrom::previous;
    Nms nms = Nms::strict;
    Border border = Border::window;

    /// Formats that keep every bit of M and of the block sum (no floor(/32), no floor(/16)),
    /// with wide enough response words: the "no truncation" ablation.
    static Formats untruncated();
    std::string describe() const;
};

/// A frame's response image. Values are the hardware's resp_w-bit responses, or for
/// KRule::exact the exact 25*(AC - B^2) - (A+C)^2 (k = 1/25 without a division).
struct Response {
    int width = 0, height = 0;
    std::vector<std::int64_t> r;   ///< row-major, width*height; 0 where not computed
    int x0 = 0, x1 = 0, y0 = 0, y1 = 0;   ///< candidate centres [x0, x1) x [y0, y1)
    std::int64_t max = 0;          ///< max of r over the candidate centres
    std::int64_t at(int y, int x) const { return r[static_cast<size_t>(y) * width + x]; }
};

/// The corners of one frame and the values that made them.
struct FrameCorners {
    std::vector<std::uint8_t> mask;   ///< row-major, 1 = corner
    std::int64_t max = 0;             ///< this frame's response maximum
    std::int64_t thr = 0;             ///< the threshold applied
    long count = 0;
};

class SpecModel {
public:
    explicit SpecModel(const Options& o = {});
    const Options& options() const { return o_; }

    /// The response at every computable pixel (see Border).
    void response(const Image& img, Response& out) const;
    /// The threshold a frame gets from a maximum, per the ThrRule.
    std::int64_t threshold_for(std::int64_t max) const;
    /// The maximum the hardware holds after reset (most negative resp_w-bit value): it sets
    /// the first frame's threshold.
    std::int64_t reset_max() const;
    /// Thresholded 3x3 local maxima over the candidate centres, one threshold for all.
    void corners(const Response& r, std::int64_t thr, std::vector<std::uint8_t>& mask) const;
    /// The same with a threshold per centre (for comparing with the cycle model, whose
    /// threshold can change within a frame).
    void corners(const Response& r, const std::function<std::int64_t(int x, int y)>& thr_at,
                 std::vector<std::uint8_t>& mask) const;

    /// A stream of frames: responses of all frames in parallel, then each frame's corners
    /// with the threshold from the previous frame's maximum (or its own, MaxFrom::current).
    /// `prev_max` is the maximum before the first frame (reset_max() for a fresh stream)
    /// and is updated to the last frame's. threads <= 0: all cores.
    std::vector<FrameCorners> run(const std::vector<const Image*>& frames, std::int64_t& prev_max,
                                  int threads = 0) const;
    /// The same in a caller's arena: a stream run a batch at a time creates no arena per batch.
    std::vector<FrameCorners> run(const std::vector<const Image*>& frames, std::int64_t& prev_max,
                                  tbb::task_arena& arena) const;

private:
    Options o_;
};

/// The spec model over a stream fed in order, a batch of frames at a time (one frame or
/// many): the maximum carried from one batch to the next as SpecModel::run carries it within
/// one, so each frame's threshold comes from the frame before it, whatever the batches.
class SpecStream {
public:
    /// `before`: the frame before the stream, for its maximum only (when the options take
    /// the previous frame's maximum); without it the stream starts from the reset value.
    explicit SpecStream(const Options& o = {}, const Image* before = nullptr);
    /// The next frames' corners (responses in parallel in `arena`).
    std::vector<FrameCorners> run(const std::vector<const Image*>& frames, tbb::task_arena& arena);
    /// The same on `threads` threads (<= 0: all cores).
    std::vector<FrameCorners> run(const std::vector<const Image*>& frames, int threads = 0);
    const SpecModel& model() const { return m_; }

private:
    SpecModel m_;
    std::int64_t prev_;
};

/// Number of corners in a mask.
long count_corners(const std::vector<std::uint8_t>& mask);

}  // namespace hc::spec
