// results_json.cpp: the JSON of a pair's matches (matching.hpp: PairResult) and of summed
// counts (pipeline.hpp: Totals), as sharded runs carry them from a worker to the merge.
#include "mapping/landmarks/pipeline.hpp"

#include <nlohmann/json.hpp>

namespace hc::landmarks {

using nlohmann::json;

namespace {

json keypoints_json(const std::vector<cv::KeyPoint>& v) {
    json a = json::array();
    for (const auto& k : v) a.push_back({k.pt.x, k.pt.y, k.size, k.angle, k.response, k.octave, k.class_id});
    return a;
}

std::vector<cv::KeyPoint> keypoints_from(const json& a) {
    std::vector<cv::KeyPoint> v;
    for (const auto& k : a)
        v.emplace_back(cv::Point2f(k.at(0).get<float>(), k.at(1).get<float>()), k.at(2).get<float>(), k.at(3).get<float>(),
                       k.at(4).get<float>(), k.at(5).get<int>(), k.at(6).get<int>());
    return v;
}

json mat_json(const cv::Mat& m) {
    static const char* hex = "0123456789abcdef";
    const cv::Mat c = m.isContinuous() ? m : m.clone();
    std::string s;
    const auto* p = c.data;
    for (std::size_t i = 0; i < c.total() * c.elemSize(); ++i) {
        s += hex[p[i] >> 4];
        s += hex[p[i] & 15];
    }
    return {{"type", m.type()}, {"rows", m.rows}, {"cols", m.cols}, {"hex", s}};
}

cv::Mat mat_from(const json& j) {
    cv::Mat m(j.at("rows").get<int>(), j.at("cols").get<int>(), j.at("type").get<int>());
    const std::string& s = j.at("hex").get_ref<const std::string&>();
    if (s.size() != 2 * m.total() * m.elemSize()) throw InputError("landmarks: a descriptor matrix has the wrong size");
    auto nib = [](char c) { return c <= '9' ? c - '0' : c - 'a' + 10; };
    for (std::size_t i = 0; i < m.total() * m.elemSize(); ++i) m.data[i] = static_cast<uchar>(nib(s[2 * i]) * 16 + nib(s[2 * i + 1]));
    return m;
}

}  // namespace

void to_json(json& j, const PairResult& r) {
    json matches = json::array();
    for (const auto& m : r.matches)
        matches.push_back({m.left.x, m.left.y, m.right.x, m.right.y, m.distance, m.left_index, m.right_index, m.epipolar, m.truth});
    j = {{"name", r.name},
         {"keypoints_left", r.keypoints_left},
         {"keypoints_right", r.keypoints_right},
         {"matches", matches},
         {"has_truth", r.has_truth},
         {"descriptor_bytes", r.descriptor_bytes},
         {"seconds", r.seconds},
         {"desc_left", mat_json(r.desc_left)},
         {"kp_left", keypoints_json(r.kp_left)},
         {"kp_right", keypoints_json(r.kp_right)}};
}

void from_json(const json& j, PairResult& r) {
    r.name = j.at("name");
    r.keypoints_left = j.at("keypoints_left");
    r.keypoints_right = j.at("keypoints_right");
    for (const auto& a : j.at("matches")) {
        StereoMatch m;
        m.left = {a.at(0).get<float>(), a.at(1).get<float>()};
        m.right = {a.at(2).get<float>(), a.at(3).get<float>()};
        m.distance = a.at(4);
        m.left_index = a.at(5);
        m.right_index = a.at(6);
        m.epipolar = a.at(7);
        m.truth = a.at(8);
        r.matches.push_back(m);
    }
    r.has_truth = j.at("has_truth");
    r.descriptor_bytes = j.at("descriptor_bytes");
    r.seconds = j.at("seconds");
    r.desc_left = mat_from(j.at("desc_left"));
    r.kp_left = keypoints_from(j.at("kp_left"));
    r.kp_right = keypoints_from(j.at("kp_right"));
}

void to_json(json& j, const Totals& t) {
    j = {{"keypoints", t.keypoints}, {"all", t.all}, {"correct", t.correct}, {"truth_known", t.truth_known},
         {"truth_correct", t.truth_correct}, {"seconds", t.seconds}, {"pairs", t.pairs}};
}

void from_json(const json& j, Totals& t) {
    t.keypoints = j.at("keypoints");
    t.all = j.at("all");
    t.correct = j.at("correct");
    t.truth_known = j.at("truth_known");
    t.truth_correct = j.at("truth_correct");
    t.seconds = j.at("seconds");
    t.pairs = j.at("pairs");
}

}  // namespace hc::landmarks
