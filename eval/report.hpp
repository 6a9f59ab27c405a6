// report.hpp: the outputs of `harris-cosim eval` (Markdown summary, per-frame CSV, JSON
// totals, overlay PNGs, recall/precision plot), each written atomically.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "eval/eval.hpp"

namespace hc::eval {

struct FrameRow {
    int frame = 0;          ///< index in the stream
    std::string name;
    int pair = 0;
    bool scored = false;
    Confusion c;
    long source_corners = 0, reference_corners = 0;
    std::int64_t thr = 0, max = 0;
};

struct AblationRow {
    std::string name;       ///< what was switched back to ideal
    std::string options;    ///< SpecModel options description
    Confusion c;
};

struct DeviationRow {
    std::string cause;
    std::string pixels;     ///< pixels affected (description with counts)
    long corners = 0;       ///< corners it changes (spec corners lost, or differing pixels)
    std::string measured;   ///< how it was measured
};

/// One sequence of a report over several (per-sequence totals of its scored frames).
struct SequenceRow {
    std::string sequence;
    int first_pair = 0, last_pair = 0;   ///< stereo pairs first..last, both included
    int frames = 0, scored = 0;
    Confusion c;
};

struct Report {
    std::string source, stream, command;
    int threads = 0;
    double seconds_source = 0, seconds_reference = 0, seconds_total = 0;
    std::vector<FrameRow> frames;
    std::vector<SequenceRow> sequences;   ///< empty: a single stream
    Confusion total;
    std::vector<AblationRow> ablation;
    std::vector<DeviationRow> deviations;
    std::vector<std::string> notes;
    std::vector<std::string> overlays;   ///< overlay PNG files written (names in the output directory)
    /// rtl source: reads where the netlist and the cycle model run in lock step disagree (a
    /// regression failure: the command exits 1 after writing the report); 0 for the others
    long rtl_mismatches = 0;
};

/// summary.md, frames.csv, totals.json (and sequences.csv with several sequences). Timings
/// appear only when measured (seconds_total > 0): a report folded from the parts of a
/// sharded run carries none, so its CSV and JSON are the same whichever way it was split.
void write_reports(const std::filesystem::path& out, const Report& r);
/// Overlay: the frame in grey, both = green, source only = red, reference only = blue.
void write_overlay(const std::filesystem::path& file, const Image& img, const std::vector<std::uint8_t>& src,
                   const std::vector<std::uint8_t>& ref);
/// The rtl source is also a regression of the netlist against the cycle model: throws
/// MismatchError (status 1) naming the count and the report directory `out` when any read
/// disagreed (Report::rtl_mismatches > 0); nothing for the other sources.
void require_rtl_agreement(const Report& r, const std::filesystem::path& out);
/// recall/precision per scored frame via gnuplot; false (with a warning) if gnuplot is missing.
bool write_plot(const std::filesystem::path& out, const Report& r);

}  // namespace hc::eval
