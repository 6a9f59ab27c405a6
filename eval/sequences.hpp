// sequences.hpp: the evaluation of several KITTI-layout sequences, computed in parts that
// fold into one report exactly as a single run of the whole would write it.
//
// Each sequence is streamed from its own reset (as the thesis does for one). A part is a
// range of stereo pairs of one sequence: the spec model and the OpenCV reference are per
// frame (a frame's threshold needs only the previous frame's maximum, recomputed from that
// frame), the RTL source runs whole sequences, and the cycle source starts a part at a
// CycleCheckpoint (eval.hpp) taken by a serial pre-pass, so every part's frames come out
// as the serial run computes them. merge_parts() folds parts (in sequence and frame order)
// into a Report without timings: the same data, byte for byte, however the work was split.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/eval.hpp"
#include "eval/report.hpp"

namespace hc::eval {


/// One part of a sequence's evaluation.
struct PartInput {
    Source source = Source::spec;
    frames::FrameFeed* feed = nullptr;   ///< frames [offset, offset + size) of the sequence's stream,
                                         ///< read as the part reaches them
    int offset = 0;
    int first = 0, last = 0;          ///< the frames reported, [first, last)
    int frames_total = 0;             ///< frames in the sequence's stream
    int first_pair = 0, last_pair = 0;   ///< the sequence's first and last stereo pair (scoring)
    /// spec, ablation and deviations need frame first-1 (for its maximum) when first > 0;
    /// the cycle source needs frame `last` when last < frames_total (its preloaded columns)
    const CycleCheckpoint* start = nullptr;   ///< cycle: where frame `first` starts
    long end_write = 0;                       ///< cycle: the next part's checkpoint writes
    bool ablation = true;
    int threads = 0;
    /// called with each reported frame's source and reference masks (overlays)
    std::function<void(int frame, const Image& img, const std::vector<std::uint8_t>& source,
                       const std::vector<std::uint8_t>& reference)> on_masks;
};

/// What a part contributes.
struct Part {
    std::string sequence;
    int width = 0, height = 0;
    int first_pair = 0, last_pair = 0;   ///< the sequence's pair range (for the description)
    std::vector<FrameRow> rows;          ///< frames [first, last)
    std::vector<long> publications;      ///< cycle: maxima published while each frame streamed
    long next_publications = 0;          ///< cycle: published during the next frame's preload
    std::int64_t next_max = 0;
    std::vector<Confusion> ablation;     ///< per variant of ablation_variants()
    /// deviation counts (cycle) and counters
    long lost_col = 0, outside = 0, drift = 0, residual = 0, diff_total = 0, scored_frames = 0;
    long mixed_windows = 0, max_publications = 0, writes = 0, reads = 0, rtl_mismatches = 0;
    /// cycle: chain_digest() of the checkpoint the part started from (empty: reset) and of
    /// the state where it stopped (empty: the stream's end); a merge checks that each
    /// part's end equals the next part's start
    std::string start_digest, end_digest;
    int chain_checked = 0;               ///< boundaries within the sequence whose digests agreed
    double seconds_source = 0, seconds_reference = 0;   ///< not part of the merged data

    nlohmann::json to_json() const;
    static Part from_json(const nlohmann::json& j);   ///< InputError when malformed
};

/// The ablation: one approximation switched back to ideal at a time (spec model).
struct AblationVariant {
    std::string name;
    spec::Options opt;
};
std::vector<AblationVariant> ablation_variants();

/// Computes one part (throws as evaluate() does).
Part evaluate_part(const PartInput& in);

/// Parts given in order folded into one per sequence: the data of a merged run, the same
/// however the sequences were split (timings dropped).
std::vector<Part> fold_sequences(const std::vector<Part>& parts, Source source);

/// The report of parts given in order (a sequence's parts contiguous and in frame order):
/// rows, per-sequence totals, the total, ablation and deviations; no timings, command or
/// threads (the caller sets those it wants).
Report merge_parts(const std::vector<Part>& parts, Source source, bool ablation);

}  // namespace hc::eval
