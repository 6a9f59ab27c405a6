// eval.hpp: the thesis's quality evaluation (Schulz 2015, section 6.3.2) of a corner
// source against the OpenCV reference (docs/metrics.md).
//
// Protocol: frames are streamed L0 R0 L1 R1 ...; the first stereo pair only seeds the
// threshold and is not scored; for the cycle source the last pair is incomplete (its last
// windows come back only while the next pair is written) and is not scored either. Every
// pixel of every scored image is a TP, TN, FP or FN of the source against the reference,
// summed over the sequence.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cosim/corners/corners.hpp"
#include "io/frames/frames.hpp"
#include "model/driver/host_driver.hpp"
#include "model/image/image.hpp"
#include "model/spec/opencv_reference.hpp"
#include "model/spec/spec_model.hpp"

namespace hc::eval {

struct Confusion {
    std::uint64_t tp = 0, tn = 0, fp = 0, fn = 0;
    void add(const Confusion& o) { tp += o.tp; tn += o.tn; fp += o.fp; fn += o.fn; }
    std::uint64_t total() const { return tp + tn + fp + fn; }
    double recall() const { return tp + fn ? double(tp) / double(tp + fn) : 0.0; }
    double specificity() const { return tn + fp ? double(tn) / double(tn + fp) : 0.0; }
    double precision() const { return tp + fp ? double(tp) / double(tp + fp) : 0.0; }
    double f1() const {
        const double p = precision(), r = recall();
        return p + r > 0 ? 2 * p * r / (p + r) : 0.0;
    }
};

/// Per-pixel classification of `test` against `ref` (both row-major masks, same size).
Confusion classify(const std::vector<std::uint8_t>& test, const std::vector<std::uint8_t>& ref);

/// The co-processor's corner sources: the rows of corners::source_table().
using corners::Source;
using corners::parse_source;
using corners::source_name;

/// The frames of one evaluation: a stream of stereo pairs (2 frames each).
using Stream = frames::Stream;

/// Corner masks of a source for every frame of a stream (empty mask: frame not produced).
struct SourceRun {
    std::vector<std::vector<std::uint8_t>> masks;
    std::vector<std::int64_t> thr;     ///< threshold in effect at the frame's first window
    std::vector<std::int64_t> max;     ///< the frame's own response maximum (spec) or the
                                       ///< maximum published while it streamed (cycle)
    double seconds = 0;
};

/// The cycle model through the host driver, with everything the deviation catalog needs.
struct CycleRun : SourceRun {
    /// the threshold each read window was thresholded with (per frame, row-major; -1 = none)
    std::vector<std::vector<std::int64_t>> thr_map;
    long writes = 0, reads = 0;
    long mixed_windows = 0;            ///< windows entering find-max that mix two frames
    long max_publications = 0;         ///< times find-max published a maximum
    std::vector<long> publications_in_frame;   ///< publications while each frame streamed
    /// a span that stops before the stream's end: the publications (and the last maximum)
    /// while the next frame's first columns were written, which belong to that frame
    long next_publications = 0;
    std::int64_t next_max = 0;
};

/// A point of a stream where the cycle model resumes exactly: before the first write of a
/// frame's body (after its first columns were preloaded by the previous frame's tail).
struct CycleCheckpoint {
    int frame = 0;                   ///< the frame whose body starts here
    std::string model;               ///< HarrisTop::save_state(): every register
    DriverState driver;              ///< the host driver's position
    long writes = 0;                 ///< writes before this point
    std::vector<WritePos> recent;    ///< where the last writes came from (oldest first), for
                                     ///< the stage tags of windows still in the pipeline
};
nlohmann::json to_json(const CycleCheckpoint& c);
CycleCheckpoint checkpoint_from_json(const nlohmann::json& j);   ///< InputError when malformed

/// Which part of a stream a cycle run covers. The stream handed to it holds frames
/// [offset, offset + size) of a stream of `frames_total` frames; the run reports frames
/// [first, last) and starts at `start` (none: reset, frame 0), stopping after `end_write`
/// writes (0: at the stream's end), which must be a checkpoint's `writes`.
struct CycleSpan {
    int offset = 0, first = 0, last = 0, frames_total = 0;
    const CycleCheckpoint* start = nullptr;
    long end_write = 0;
};

/// What the fast pre-pass needs from a stream's start: the checkpoint at frame 1's body and
/// how writes and find-max's period counter advance per frame. The control registers
/// (load control, input converter counters, stage enables) do not depend on the pixels, and
/// every frame after the first is written the same way, so they repeat at each frame's body
/// start; only the write count and the period counter advance (the counter by the frame's
/// enabled steps, modulo the period: the drift of docs/deviations.md).
struct CheckpointBase {
    CycleCheckpoint at1;
    long writes_per_frame = 0;
    long count_per_frame = 0;   ///< find-max counter advance per frame, modulo the period
    long period = 0;
};
/// From a serial run over frames 0..2 (the stream holds at least those, from frame 0).
CheckpointBase checkpoint_base(const Stream& s, const Formats& f, int frames_total);
/// The fast pre-pass: the checkpoint before frame `to`'s body from a warm-up over the
/// `warm` frames before it: the model starts at frame to-warm's body with the control
/// registers of `base` (rebased) and whatever data registers it holds, and the warm-up
/// flushes those: the pipeline within a column, find-max's maximum after its second
/// complete period (checked: fewer than 3 publications in the warm-up is InternalError).
/// The stream holds frames [offset, ...) including to-warm .. to; to - warm >= 1.
/// `min_publications` below 3 weakens that check (for tests of the chain check, which must
/// catch the checkpoint such a warm-up gives).
CycleCheckpoint warm_checkpoint(const Stream& s, const Formats& f, int offset, int frames_total,
                                const CheckpointBase& base, int to, int warm, int min_publications = 3);

/// The spec model over a stream. The first frame's threshold comes from `before`'s maximum
/// (its response only) when given and the options take the previous frame's maximum, else
/// from the reset value.
SourceRun run_spec(const Stream& s, const spec::Options& o, int threads, const Image* before = nullptr);
/// Frame k of the whole stream (an in-memory Stream, or a frames::FrameFeed), asked for
/// as the host driver reaches it; the run keeps it only while it streams.
using FrameAt = std::function<std::shared_ptr<const Image>(int frame)>;

/// One frame of a cycle run, handed on once no later write can change it.
struct CycleFrame {
    int frame = 0;                          ///< index in the whole stream
    std::vector<std::uint8_t> mask;         ///< the corners read back, row-major
    /// the threshold each window centre was thresholded with: thr_values[thr_index[pixel] - 1]
    /// (thr_index 0: no window thresholded there); a frame sees one or two thresholds
    std::vector<std::int64_t> thr_values;
    std::vector<std::uint8_t> thr_index;
    std::int64_t thr = 0;                   ///< at the frame's first thresholded window
    std::int64_t max = 0;                   ///< the last maximum published while it streamed
    long publications = 0;                  ///< publications while it streamed
    std::int64_t thr_at(std::size_t pixel) const {
        return thr_index[pixel] ? thr_values[thr_index[pixel] - 1u] : -1;
    }
};

/// A cycle run's counters over its span (what CycleRun holds besides the frames).
struct CycleCounts {
    long writes = 0, reads = 0, mixed_windows = 0, max_publications = 0;
    long next_publications = 0;   ///< see CycleRun
    std::int64_t next_max = 0;
    /// a span that stops at `end_write`: chain_digest() of the state there (the model's
    /// registers, the driver's position, the recent writes), which must equal the digest
    /// of the next part's starting checkpoint; empty at the stream's end
    std::string end_digest;
    double seconds = 0;
};

/// The digest a chain check compares: 16 hex digits over every field of the checkpoint.
std::string chain_digest(const CycleCheckpoint& c);

/// The cycle model over a span, streaming: frames are asked of `frames` as the driver
/// reaches them (at most two held), the positions of only the last writes are kept (a
/// ring; a stage tag older than it is InternalError), and each reported frame goes to
/// `on_frame` in order once complete. Memory does not grow with the span.
CycleCounts run_cycle(const FrameAt& frames, const Geometry& g, const Formats& f, const CycleSpan& span, bool progress,
                      const std::function<void(CycleFrame&&)>& on_frame);
/// The whole stream from reset.
CycleRun run_cycle(const Stream& s, const Formats& f, bool progress);
/// A span of a stream (see CycleSpan); vectors are indexed from span.first.
CycleRun run_cycle(const Stream& s, const Formats& f, const CycleSpan& span, bool progress);
/// The checkpoint before frame `to`'s body: the model run from `from` (none: reset) over
/// the stream (frames [offset, offset + size) of `frames_total`), which must hold the frames
/// from `from`'s through `to`. The serial pre-pass of a run split within a sequence.
CycleCheckpoint cycle_checkpoint(const Stream& s, const Formats& f, int offset, int frames_total,
                                 const CycleCheckpoint* from, int to);

/// The reference masks of all frames (in parallel).
std::vector<std::vector<std::uint8_t>> run_reference(const Stream& s, const spec::ReferenceOptions& o,
                                                     int threads, std::vector<double>* max = nullptr);

}  // namespace hc::eval
