// sequences.cpp: several sequences, parts of them, and their fold into one report
// (sequences.hpp). The parts themselves are computed in evaluate.cpp (evaluate_part).
#include "eval/sequences.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

namespace hc::eval {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json confusion_json(const Confusion& c) { return json::array({c.tp, c.tn, c.fp, c.fn}); }
Confusion confusion_of(const json& j) {
    Confusion c;
    c.tp = j.at(0);
    c.tn = j.at(1);
    c.fp = j.at(2);
    c.fn = j.at(3);
    return c;
}

/// Adds the counts of part `p` (all but the chain checks) to `into`.
void add_counts(Part& into, const Part& p) {
    into.lost_col += p.lost_col;
    into.outside += p.outside;
    into.drift += p.drift;
    into.residual += p.residual;
    into.diff_total += p.diff_total;
    into.scored_frames += p.scored_frames;
    into.mixed_windows += p.mixed_windows;
    into.max_publications += p.max_publications;
    into.writes += p.writes;
    into.reads += p.reads;
    into.rtl_mismatches += p.rtl_mismatches;
}

/// The cycle source's deviations from the spec (each with its count in `sum`) and notes.
void add_cycle_deviations(Report& rep, const Part& sum, const std::set<std::pair<int, int>>& geometries) {
    // the columns and borders each geometry loses, one clause per geometry
    std::string lost, outside;
    for (auto [w, h] : geometries) {
        const Geometry g{w, h};
        const int x_lost = w / 2 - 1, x_lost2 = x_lost + g.dj();
        const int x_hw_max = w / 2 - 1 + g.dj(), y_hw_max = h / 2 - 1 + g.di();
        const long outside_px = static_cast<long>((w - 4) - x_hw_max) * (h - 7) +
                                static_cast<long>((h - 4) - y_hw_max) * (w - 7);
        const std::string at = geometries.size() > 1 ? fmt::format(" ({}x{})", w, h) : "";
        lost += fmt::format("{}columns x = {} and {} (rows 3..{}): {} pixels per frame{}", lost.empty() ? "" : "; ",
                            x_lost, x_lost2, y_hw_max, 2 * (h / 2 - 3), at);
        outside += fmt::format("{}x in {}..{} or y in {}..{}: {} pixels per frame{}", outside.empty() ? "" : "; ",
                               x_hw_max + 1, w - 4, y_hw_max + 1, h - 4, outside_px, at);
    }
    rep.deviations.push_back({"window of a row's last column latched while load is high (never processed)", lost,
                              sum.lost_col, "spec corners on those columns, summed over scored frames (the hardware reports none)"});
    rep.deviations.push_back({"find-max period (h/2-3)(w/2+3)*4 != enabled steps per frame: threshold drifts",
                              fmt::format("every processed pixel; {} maxima published over {} frames", sum.max_publications,
                                          rep.frames.size()),
                              sum.drift, "pixels where spec corners with the previous frame's maximum differ from spec corners with the threshold the cycle model applied to each window"});
    rep.deviations.push_back({"windows mixing two frames at a frame start (load not raised at frame end)",
                              fmt::format("{} windows entered find-max with columns of two frames", sum.mixed_windows), 0,
                              "window provenance tags of the cycle model; their centres have x < 3 and are never read, they only feed find-max"});
    rep.deviations.push_back({"border and last column/row of odd sizes (centres beyond the host's loops)", outside,
                              sum.outside, "spec corners there, summed over scored frames"});
    rep.deviations.push_back({"unexplained (cycle model vs spec model at the cycle model's thresholds)", "processed pixels",
                              sum.residual, "must be 0: every remaining difference is a bug"});
    rep.notes.push_back(fmt::format("Cycle vs spec corner masks differ on {} pixels of {} scored frames in total "
                                    "(pixels x,y in 3..w-4, 3..h-4).", sum.diff_total, sum.scored_frames));
    rep.notes.push_back(fmt::format("Cycle model: {} writes, {} reads.", sum.writes, sum.reads));
    if (sum.chain_checked > 0)
        rep.notes.push_back(fmt::format(
            "Sharded cycle run: chain checked at {} boundaries (at each, the cycle model's registers, the host "
            "driver's position and the recent writes where a part stopped equal the next part's starting checkpoint).",
            sum.chain_checked));
}

}  // namespace

json Part::to_json() const {
    json rows_j = json::array();
    for (const auto& r : rows)
        rows_j.push_back({r.frame, r.name, r.pair, r.scored, confusion_json(r.c), r.source_corners, r.reference_corners,
                          r.thr, r.max});
    json abl = json::array();
    for (const auto& c : ablation) abl.push_back(confusion_json(c));
    return {{"sequence", sequence},
            {"geometry", {width, height}},
            {"pairs", {first_pair, last_pair}},
            {"rows", rows_j},
            {"publications", publications},
            {"next", {next_publications, next_max}},
            {"ablation", abl},
            {"counts", {lost_col, outside, drift, residual, diff_total, scored_frames, mixed_windows, max_publications,
                        writes, reads, rtl_mismatches}},
            {"chain", {start_digest, end_digest, chain_checked}},
            {"seconds", {seconds_source, seconds_reference}}};
}

Part Part::from_json(const json& j) {
    try {
        Part p;
        p.sequence = j.at("sequence");
        p.width = j.at("geometry").at(0);
        p.height = j.at("geometry").at(1);
        p.first_pair = j.at("pairs").at(0);
        p.last_pair = j.at("pairs").at(1);
        for (const auto& r : j.at("rows")) {
            FrameRow f;
            f.frame = r.at(0);
            f.name = r.at(1);
            f.pair = r.at(2);
            f.scored = r.at(3);
            f.c = confusion_of(r.at(4));
            f.source_corners = r.at(5);
            f.reference_corners = r.at(6);
            f.thr = r.at(7);
            f.max = r.at(8);
            p.rows.push_back(f);
        }
        p.publications = j.at("publications").get<std::vector<long>>();
        p.next_publications = j.at("next").at(0);
        p.next_max = j.at("next").at(1);
        for (const auto& c : j.at("ablation")) p.ablation.push_back(confusion_of(c));
        const auto& n = j.at("counts");
        long* fields[] = {&p.lost_col, &p.outside, &p.drift, &p.residual, &p.diff_total, &p.scored_frames,
                          &p.mixed_windows, &p.max_publications, &p.writes, &p.reads, &p.rtl_mismatches};
        if (n.size() != std::size(fields)) throw InputError("eval part: " + std::to_string(n.size()) + " counts");
        for (std::size_t k = 0; k < std::size(fields); ++k) *fields[k] = n.at(k);
        p.start_digest = j.at("chain").at(0);
        p.end_digest = j.at("chain").at(1);
        p.chain_checked = j.at("chain").at(2);
        p.seconds_source = j.at("seconds").at(0);
        p.seconds_reference = j.at("seconds").at(1);
        return p;
    } catch (const json::exception& e) {
        throw InputError(std::string("eval part: ") + e.what());
    }
}

std::vector<Part> fold_sequences(const std::vector<Part>& parts, Source source) {
    const bool observed = corners::source_info(source).observed;   // parts chained by checkpoints
    std::vector<Part> out;
    for (const Part& p : parts) {
        if (out.empty() || out.back().sequence != p.sequence) {
            Part q = p;
            q.seconds_source = q.seconds_reference = 0;
            out.push_back(std::move(q));
            continue;
        }
        Part& q = out.back();
        if (p.rows.empty() || q.rows.empty() || p.rows.front().frame != q.rows.back().frame + 1)
            throw InputError(fmt::format("eval parts of sequence {} are not contiguous (frame {} follows frame {})",
                                         p.sequence, p.rows.empty() ? -1 : p.rows.front().frame,
                                         q.rows.empty() ? -1 : q.rows.back().frame));
        if (p.ablation.size() != q.ablation.size()) throw InputError("eval parts of sequence " + p.sequence + " differ in ablation");
        // the chain check: where the part before stopped is where this one started
        if (observed) {
            const FrameRow& at = p.rows.front();
            if (q.end_digest.empty() || q.end_digest != p.start_digest)
                throw SimulatorError(fmt::format(
                    "chain check failed at the boundary before frame {} ({}, stereo pair {}) of sequence {}: the part "
                    "before it stopped in state {}, the part after it started from checkpoint {}; the sharded cycle run "
                    "would differ from the serial one (a warm-up too short to flush the model?), so no report is written",
                    at.frame, at.name, at.pair, p.sequence, q.end_digest.empty() ? "(not recorded)" : q.end_digest,
                    p.start_digest.empty() ? "(reset)" : p.start_digest));
            q.chain_checked += 1 + p.chain_checked;
        }
        for (std::size_t k = 0; k < p.rows.size(); ++k) {
            FrameRow row = p.rows[k];
            // the first frame's maximum: the last one published while it streamed, which
            // is the previous part's when none was published in this part's share of it
            if (observed && k == 0 && q.next_publications > 0 && p.publications.at(0) == 0)
                row.max = q.next_max;
            q.rows.push_back(row);
        }
        if (observed) {
            std::vector<long> pub = p.publications;
            pub.at(0) += q.next_publications;
            q.publications.insert(q.publications.end(), pub.begin(), pub.end());
        }
        q.next_publications = p.next_publications;
        q.next_max = p.next_max;
        q.end_digest = p.end_digest;
        for (std::size_t v = 0; v < p.ablation.size(); ++v) q.ablation[v].add(p.ablation[v]);
        add_counts(q, p);
    }
    return out;
}

Report merge_parts(const std::vector<Part>& parts, Source source, bool ablation) {
    const bool observed = corners::source_info(source).observed;   // the deviation catalog
    Report rep;
    rep.source = source_name(source);
    const auto variants = ablation_variants();
    std::vector<Confusion> abl(variants.size());
    Part sum;   // the counts, added
    std::set<std::pair<int, int>> geometries;
    for (const Part& p : fold_sequences(parts, source)) {
        rep.sequences.push_back({p.sequence, p.first_pair, p.last_pair, 0, 0, {}});
        rep.stream += fmt::format("{}KITTI sequence {}, stereo pairs {}..{} ({}x{})", rep.stream.empty() ? "" : "; ",
                                  p.sequence, p.first_pair, p.last_pair, p.width, p.height);
        SequenceRow& q = rep.sequences.back();
        for (const FrameRow& row : p.rows) {
            ++q.frames;
            if (row.scored) {
                ++q.scored;
                q.c.add(row.c);
                rep.total.add(row.c);
            }
            rep.frames.push_back(row);
        }
        if (ablation) {
            if (p.ablation.size() != abl.size()) throw InputError("eval part: ablation rows differ from the variants");
            for (std::size_t v = 0; v < abl.size(); ++v) abl[v].add(p.ablation[v]);
        }
        add_counts(sum, p);
        sum.chain_checked += p.chain_checked;
        geometries.insert({p.width, p.height});
    }
    if (rep.sequences.size() == 1) rep.sequences.clear();   // a single stream: no per-sequence table
    rep.rtl_mismatches = sum.rtl_mismatches;
    if (corners::source_info(source).needs_simulator)
        rep.notes.push_back(fmt::format(
            "RTL source: GHDL-synthesised netlist under Verilator (gate passed), {} reads disagreeing with the "
            "cycle model run in lock step; the thr/max columns are not observed on the netlist (-1).",
            sum.rtl_mismatches));
    if (ablation) {
        for (std::size_t v = 0; v < abl.size(); ++v)
            rep.ablation.push_back({variants[v].name, variants[v].opt.describe(), abl[v]});
        rep.notes.push_back("Ablation rows score every pair but the first (the spec model has no incomplete last pair).");
    }
    if (observed) add_cycle_deviations(rep, sum, geometries);
    return rep;
}

}  // namespace hc::eval
