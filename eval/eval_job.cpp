// eval_job.cpp: the "eval" job kind (eval_job.hpp).
#include "eval/eval_job.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "eval/sequences.hpp"
#include "io/frames/frames.hpp"

namespace hc::eval {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// Frames of warm-up before a cycle checkpoint, tried in order: find-max publishes a little
/// less than once per frame (the drift) and needs three publications after the pipeline has
/// flushed, which the shortest warm-up sees unless its period counter starts just past a
/// publication; a warm-up that sees fewer (warm_checkpoint refuses it) is repeated
/// with the next one.
constexpr int kWarmFrames[] = {3, 4, 8};
constexpr int kWarmFramesMax = 8;

/// Stereo pairs [first, last) of a sequence, as a job selects them.
util::Range sequence_pairs(const fs::path& kitti, const std::string& seq, util::Range r, const std::string& what) {
    const frames::KittiSequence k = frames::open_kitti(kitti, seq);
    const int last = std::min(r.last, k.pairs());
    if (last - r.first < 2)
        throw InputError(fmt::format("{} gives {} stereo pair(s) of KITTI sequence {} ({} has {}); at least 2 are needed",
                                     what, std::max(0, last - r.first), seq, k.root.string(), k.pairs()));
    return {r.first, last};
}

/// Parts per sequence: one each, the remaining shards in proportion to the pairs (largest
/// remainder), never more parts than pairs.
std::vector<int> parts_per_sequence(const std::vector<int>& pairs, int shards) {
    const int n = static_cast<int>(pairs.size());
    std::vector<int> k(n, 1);
    const long total = std::accumulate(pairs.begin(), pairs.end(), 0L);
    int extra = std::max(0, shards - n);
    std::vector<std::pair<double, int>> rem;
    for (int s = 0; s < n; ++s) {
        const double share = static_cast<double>(shards) * pairs[s] / static_cast<double>(total);
        const int whole = std::clamp(static_cast<int>(share) - 1, 0, std::min(extra, pairs[s] - 1));
        k[s] += whole;
        extra -= whole;
        rem.push_back({share - static_cast<int>(share), s});
    }
    std::stable_sort(rem.begin(), rem.end(), [](auto& a, auto& b) { return a.first > b.first; });
    for (bool grew = true; extra > 0 && grew;) {
        grew = false;
        for (auto [r, s] : rem)
            if (extra > 0 && k[s] < pairs[s]) {
                ++k[s];
                --extra;
                grew = true;
            }
    }
    return k;
}

json run_eval_shard(const json& common, const json& shard, std::size_t) {
    cv::setNumThreads(1);   // frames run in parallel; OpenCV's own threads would oversubscribe
    const fs::path kitti = common.at("kitti").get<std::string>();
    const std::string seq = shard.at("sequence");
    const int p0 = shard.at("pairs").at(0), p1 = shard.at("pairs").at(1);
    const int a = shard.at("part").at(0), b = shard.at("part").at(1);
    // the pair before (its right frame's maximum sets the first threshold) and the pair
    // after (the cycle model preloads its first columns before this part's last reads)
    const int lo = std::max(p0, a - 1), hi = std::min(p1, b + 1);
    const std::string what = fmt::format("pairs {}:{} of sequence {}", lo, hi, seq);
    frames::FrameFeed s = frames::open_kitti_feed(kitti, seq, {lo, hi}, what, 1);
    std::optional<CycleCheckpoint> start;
    if (!shard.at("start").is_null()) start = checkpoint_from_json(shard.at("start"));
    PartInput in;
    in.source = parse_source(common.at("source"));
    in.feed = &s;
    in.offset = 2 * (lo - p0);
    in.first = 2 * (a - p0);
    in.last = 2 * (b - p0);
    in.frames_total = 2 * (p1 - p0);
    in.first_pair = p0;
    in.last_pair = p1 - 1;
    in.start = start ? &*start : nullptr;
    in.end_write = shard.at("end_write");
    in.ablation = common.at("ablation");
    in.threads = common.at("threads");
    std::fprintf(stderr, "eval shard: %s source, sequence %s, pairs %d..%d%s\n", source_name(in.source).c_str(), seq.c_str(), a, b - 1,
                 start ? fmt::format(" from the checkpoint after {} writes", start->writes).c_str() : "");
    return evaluate_part(in).to_json();
}

json merge_eval(const json& common, const std::vector<json>& data) {
    const Source source = parse_source(common.at("source"));
    std::vector<Part> parts;
    for (const auto& d : data) parts.push_back(Part::from_json(d));
    json seqs = json::array();
    for (const auto& p : fold_sequences(parts, source)) seqs.push_back(p.to_json());
    return {{"source", common.at("source")}, {"ablation", common.at("ablation")}, {"sequences", seqs}};
}

}  // namespace

cluster::Manifest eval_manifest(const EvalJob& j) {
    const Source source = parse_source(j.source);
    if (j.sequences.empty()) throw InputError("eval: no sequence given");
    frames::check_kitti_sequences(j.kitti, j.sequences);
    std::vector<util::Range> ranges;
    std::vector<int> pairs;
    for (const auto& q : j.sequences) {
        ranges.push_back(sequence_pairs(j.kitti, q, j.pairs, j.pairs_flag));
        pairs.push_back(ranges.back().last - ranges.back().first);
    }
    const int n = static_cast<int>(j.sequences.size());
    // a source run by the simulators runs whole sequences; the others split them in parts
    const std::vector<int> k = corners::source_info(source).needs_simulator ? std::vector<int>(n, 1)
                                                           : parts_per_sequence(pairs, std::max(j.shards, n));
    cluster::Manifest m;
    m.job = "eval";
    m.common = {{"source", source_name(source)}, {"kitti", fs::absolute(j.kitti).lexically_normal().string()},
                {"ablation", j.ablation}, {"threads", j.threads}};
    for (int s = 0; s < n; ++s) {
        const auto [p0, p1] = ranges[s];
        const auto parts = cluster::split_range(p0, p1, k[s]);
        // the pre-pass: each part's checkpoint from a warm-up over the frames before it
        // (warm_checkpoint), or from reset for a part starting within the first frames
        std::vector<json> starts(parts.size());
        std::vector<long> end_writes(parts.size(), 0);
        if (corners::source_info(source).observed && parts.size() > 1) {
            const int total = 2 * (p1 - p0);
            const auto load = [&](int a, int b) {   // pairs [a, b) of the sequence
                return frames::load_kitti_stream(j.kitti, j.sequences[s], {a, b}, j.pairs_flag, j.threads, 1);
            };
            std::optional<CheckpointBase> base;
            for (std::size_t t = 1; t < parts.size(); ++t) {
                const int to_pair = static_cast<int>(parts[t].first), to = 2 * (to_pair - p0);
                CycleCheckpoint c;
                if (to - kWarmFramesMax < 1) {
                    std::fprintf(stderr, "eval: checkpoint of sequence %s at pair %d (from reset)\n", j.sequences[s].c_str(), to_pair);
                    c = cycle_checkpoint(load(p0, to_pair + 1), Formats{}, 0, total, nullptr, to);
                } else {
                    if (!base) base = checkpoint_base(load(p0, p0 + 2), Formats{}, total);
                    int held_from = -1;   // the first pair of `held`, which ends at pair to_pair
                    Stream held;
                    for (const int warm : kWarmFrames) {
                        const int from_pair = p0 + (to - warm) / 2;
                        if (held_from != from_pair) {
                            held = load(from_pair, to_pair + 1);
                            held_from = from_pair;
                        }
                        std::fprintf(stderr, "eval: checkpoint of sequence %s at pair %d (warm-up of %d frames)\n",
                                     j.sequences[s].c_str(), to_pair, warm);
                        try {
                            c = warm_checkpoint(held, Formats{}, 2 * (from_pair - p0), total, *base, to, warm);
                            break;
                        } catch (const InternalError& e) {
                            if (warm == kWarmFramesMax) throw;
                            std::fprintf(stderr, "eval: %s: a longer warm-up\n", e.what());
                        }
                    }
                }
                starts[t] = to_json(c);
                end_writes[t - 1] = c.writes;
            }
        }
        const frames::KittiSequence ks = frames::open_kitti(j.kitti, j.sequences[s]);
        const Image first = frames::load_image(ks.left.at(static_cast<std::size_t>(p0)));
        for (std::size_t t = 0; t < parts.size(); ++t)
            m.shards.push_back({{"sequence", j.sequences[s]},
                                {"pairs", {p0, p1}},
                                {"part", {parts[t].first, parts[t].second}},
                                {"geometry", {first.width, first.height}},
                                {"start", starts[t]},
                                {"end_write", end_writes[t]}});
    }
    return m;
}

Report eval_report(const json& merged) {
    std::vector<Part> parts;
    for (const auto& p : merged.at("sequences")) parts.push_back(Part::from_json(p));
    return merge_parts(parts, parse_source(merged.at("source")), merged.at("ablation"));
}

void add_eval_job(cluster::JobRegistry& r) { r.add({"eval", run_eval_shard, merge_eval}); }

}  // namespace hc::eval
