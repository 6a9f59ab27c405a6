// landmarks_job.cpp: the job kind "landmarks" (landmarks_job.hpp): the descriptor comparison
// in shards of one detector over a range of a dataset's pairs (every descriptor on those corners).
#include "mapping/landmarks/landmarks_job.hpp"

#include <map>
#include <string>

#include "model/harris/formats_json.hpp"
#include "model/util/util.hpp"

namespace hc::landmarks {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string norm_name(Norm n) {
    return n == Norm::hamming ? "hamming" : n == Norm::l2 ? "l2" : "auto";
}

Dataset load_pairs(const json& common, long first, long last) {
    const fs::path root = common.at("root").get<std::string>();
    if (common.at("dataset") == "kitti") {
        const int f = common.at("first");
        return kitti_dataset(root, common.at("sequence"), {f + static_cast<int>(first), f + static_cast<int>(last)});
    }
    // the shard's scenes only, each loaded as middlebury_dataset loads it
    const auto scenes = middlebury_scenes(root);
    if (last > static_cast<long>(scenes.size()))
        throw hc::InputError("landmarks: " + root.string() + " holds " + std::to_string(scenes.size()) +
                                         " scenes, the run expects at least " + std::to_string(last));
    Dataset ds;
    for (long k = first; k < last; ++k) {
        Dataset one = middlebury_dataset(scenes[k], common.at("need_truth"));
        ds.pairs.push_back(std::move(one.pairs.at(0)));
        ds.disparity.push_back(std::move(one.disparity.at(0)));
        ds.calib.push_back(one.calib.at(0));
    }
    return ds;
}

std::string mat_hash(const cv::Mat& m) {
    const cv::Mat c = m.isContinuous() ? m : m.clone();
    return util::hex64(util::fnv1a(std::string_view(reinterpret_cast<const char*>(c.data), c.total() * c.elemSize())));
}

/// Keypoints detected on a sub-dataset starting at pair `first` carry the frame numbers of
/// the whole dataset (2k left, 2k+1 right of pair k), as compare() numbers them.
void renumber(FrameKeypoints& f, int offset) {
    f.frame += offset;
    for (auto& k : f.points) k.class_id += offset;
}

}  // namespace

cluster::Manifest landmarks_manifest(const LandmarksJob& p) {
    const auto& o = p.options;
    if (o.detectors.empty() || o.descriptors.empty())
        throw InputError("the comparison needs at least one detector and one descriptor");
    validate(o.grid);
    for (auto det : o.detectors)
        for (auto d : o.descriptors) check_combination(d, det, o.match.norm);
    cluster::Manifest m;
    m.job = "landmarks";
    json descriptors = json::array();
    for (auto d : o.descriptors) descriptors.push_back(descriptor_name(d));
    m.common = {{"dataset", p.dataset},
                {"root", fs::absolute(p.root).string()},
                {"need_truth", p.need_truth},
                {"sequence", p.sequence},
                {"first", p.first},
                {"last", p.last},
                {"pairs", p.pairs},
                {"descriptors", descriptors},
                {"grid", {o.grid.g, o.grid.h}},
                {"match", {{"norm", norm_name(o.match.norm)}, {"ratio", o.match.ratio}, {"drop_ties", o.match.drop_ties},
                           {"epipolar_px", o.match.epipolar_px}}},
                {"corners", {{"formats", json::parse(formats_to_json(o.corners.formats))},
                             {"keypoint_size", o.corners.keypoint_size},
                             {"orb_features", o.corners.orb_features}}}};
    // pair chunks per software detector, so that the shards number about p.shards
    const int per_detector = p.shards <= 0 ? 0 : std::max(1, p.shards / static_cast<int>(o.detectors.size()));
    for (auto det : o.detectors) {
        const auto chunks = is_hardware(det) ? cluster::split_items(static_cast<long>(p.pairs), 1)
                                                 : cluster::split_items(static_cast<long>(p.pairs), per_detector);
        for (auto [a, b] : chunks) m.shards.push_back({{"detector", detector_name(det)}, {"first", a}, {"last", b}});
    }
    return m;
}

std::vector<ComparisonRow> landmarks_rows(const json& merged) {
    std::vector<ComparisonRow> rows;
    for (const auto& j : merged.at("rows")) {
        ComparisonRow row;
        row.detector = parse_detector(j.at("detector"));
        row.descriptor = parse_descriptor(j.at("descriptor"));
        row.grid = {j.at("grid").at(0).get<int>(), j.at("grid").at(1).get<int>()};
        for (const auto& pj : j.at("pairs")) {
            row.pairs.push_back(pj.get<PairResult>());
            row.totals.add(row.pairs.back());
        }
        row.descriptor_bytes = row.pairs.empty() ? 0 : row.pairs.front().descriptor_bytes;
        rows.push_back(std::move(row));
    }
    return rows;
}

void add_landmarks_job(cluster::JobRegistry& r) {
    r.add({"landmarks",
            [](const json& common, const json& shard, std::size_t) {
                const long first = shard.at("first"), last = shard.at("last");
                const Detector det = parse_detector(shard.at("detector"));
                const Dataset ds = load_pairs(common, first, last);
                CornerOptions co;
                co.formats = formats_from_json(common.at("corners").at("formats"), "landmarks run formats");
                co.keypoint_size = common.at("corners").at("keypoint_size");
                co.orb_features = common.at("corners").at("orb_features");
                MatchParams mp;
                mp.norm = parse_norm(common.at("match").at("norm"));
                mp.ratio = common.at("match").at("ratio");
                mp.drop_ties = common.at("match").at("drop_ties");
                mp.epipolar_px = common.at("match").at("epipolar_px");
                const GridParams gp{common.at("grid").at(0).get<int>(), common.at("grid").at(1).get<int>()};
                auto kp = detect_dataset(ds, det, co);
                for (auto& p : kp) {
                    renumber(p.left, static_cast<int>(2 * first));
                    renumber(p.right, static_cast<int>(2 * first));
                }
                json inputs = json::array();
                for (const auto& p : ds.pairs) inputs.push_back(mat_hash(p.left) + mat_hash(p.right));
                const int threads = cv::getNumThreads();
                cv::setNumThreads(1);   // extraction and matching timed on one thread, as compare() does
                json rows = json::array();
                for (const auto& dn : common.at("descriptors")) {
                    const Descriptor d = parse_descriptor(dn);
                    json pairs = json::array();
                    for (std::size_t k = 0; k < ds.pairs.size(); ++k) {
                        const cv::Mat none;
                        json pj = json(match_pair(ds.pairs[k], kp[k], d, gp, mp,
                                                           k < ds.disparity.size() ? ds.disparity[k] : none));
                        pj["index"] = first + static_cast<long>(k);
                        pj["input_hash"] = inputs[k];
                        pairs.push_back(std::move(pj));
                    }
                    rows.push_back({{"detector", detector_name(det)}, {"descriptor", dn}, {"grid", common.at("grid")},
                                    {"pairs", std::move(pairs)}});
                }
                cv::setNumThreads(threads);
                return json{{"rows", rows}};
            },
            [](const json& common, const std::vector<json>& data) {
                // rows in order of first appearance (detector-major, then descriptor), each
                // row's pairs in shard order, which is pair order
                std::vector<std::string> order;
                std::map<std::string, json> rows;
                for (const auto& d : data)
                    for (const auto& r : d.at("rows")) {
                        const std::string key = r.at("detector").get<std::string>() + "/" + r.at("descriptor").get<std::string>();
                        if (!rows.count(key)) {
                            order.push_back(key);
                            rows[key] = {{"detector", r.at("detector")}, {"descriptor", r.at("descriptor")},
                                         {"grid", r.at("grid")}, {"pairs", json::array()}};
                        }
                        for (const auto& p : r.at("pairs")) {
                            if (p.at("index") != rows[key]["pairs"].size())
                                throw hc::InputError("landmarks: row " + key + " misses pair " +
                                                                 std::to_string(rows[key]["pairs"].size()));
                            rows[key]["pairs"].push_back(p);
                        }
                    }
                json out = {{"rows", json::array()}};
                for (const auto& k : order) {
                    if (rows[k]["pairs"].size() != common.at("pairs").get<std::size_t>())
                        throw hc::InputError("landmarks: row " + k + " has " + std::to_string(rows[k]["pairs"].size()) +
                                                         " pairs of " + common.at("pairs").dump());
                    out["rows"].push_back(std::move(rows[k]));
                }
                return out;
            }});
}

}  // namespace hc::landmarks
