// reobservation.cpp: how a descriptor changes between consecutive frames of one camera. Each
// corner of frame k is tracked into frame k+1 by pyramidal Lucas-Kanade optical flow (no
// descriptor involved), kept when the backward track returns within max_fb_px and a corner
// of frame k+1 lies within max_corner_px of the tracked position; the Hamming distance of its
// two descriptors is then compared with that of random pairs of the same two frames.
#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <opencv2/core/utility.hpp>
#include <opencv2/video/tracking.hpp>

#include "mapping/landmarks/descriptors.hpp"
#include "mapping/landmarks/pipeline.hpp"
#include "mapping/landmarks/reobservation.hpp"

namespace hc::landmarks {

namespace {

/// Described keypoints of one image: descriptors and, per row, the index of the keypoint in
/// the detector's list (descriptors may drop keypoints at the border).
struct Described {
    cv::Mat desc;
    std::vector<int> source;   ///< row -> detector index
    std::vector<int> row_of;   ///< detector index -> row, -1 when dropped
};

Described describe(const cv::Mat& img, const std::vector<cv::KeyPoint>& kp, Descriptor d, const GridParams& gp,
                   Detector det) {
    std::vector<cv::KeyPoint> k = keypoints_for(d, det, kp);
    for (size_t i = 0; i < k.size(); ++i) k[i].class_id = static_cast<int>(i);
    Described out;
    make_descriptor(d, gp)->compute(img, k, out.desc);
    out.row_of.assign(kp.size(), -1);
    for (size_t r = 0; r < k.size(); ++r) {
        out.source.push_back(k[r].class_id);
        out.row_of[static_cast<size_t>(k[r].class_id)] = static_cast<int>(r);
    }
    return out;
}

double median_of(std::vector<double> v) {
    if (v.empty()) return 0;
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

double mean_of(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / static_cast<double>(v.size());
}

}  // namespace

std::vector<std::pair<int, int>> track_corners(const cv::Mat& a, const cv::Mat& b, const std::vector<cv::KeyPoint>& ka,
                                               const std::vector<cv::KeyPoint>& kb, const ReobservationOptions& o) {
    std::vector<std::pair<int, int>> out;
    if (ka.empty() || kb.empty()) return out;
    std::vector<cv::Point2f> p0, p1, back;
    for (const auto& k : ka) p0.push_back(k.pt);
    std::vector<uchar> st, st_back;
    std::vector<float> err;
    const cv::Size win(21, 21);
    cv::calcOpticalFlowPyrLK(a, b, p0, p1, st, err, win, 3);
    cv::calcOpticalFlowPyrLK(b, a, p1, back, st_back, err, win, 3);
    // corners of b by pixel, to find the one nearest a tracked position
    std::multimap<std::pair<int, int>, int> at;
    for (size_t j = 0; j < kb.size(); ++j) at.emplace(std::pair{cvRound(kb[j].pt.x), cvRound(kb[j].pt.y)}, int(j));
    const int reach = static_cast<int>(std::ceil(o.max_corner_px));
    std::vector<int> taken(kb.size(), -1);
    std::vector<std::pair<int, int>> cand;
    for (size_t i = 0; i < p0.size(); ++i) {
        if (!st[i] || !st_back[i] || cv::norm(back[i] - p0[i]) > o.max_fb_px) continue;
        int best = -1;
        double best_d = o.max_corner_px;
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dx = -reach; dx <= reach; ++dx) {
                const auto [lo, hi] = at.equal_range({cvRound(p1[i].x) + dx, cvRound(p1[i].y) + dy});
                for (auto it = lo; it != hi; ++it) {
                    const double d = cv::norm(kb[static_cast<size_t>(it->second)].pt - p1[i]);
                    if (d <= best_d) best_d = d, best = it->second;
                }
            }
        if (best < 0) continue;
        if (taken[static_cast<size_t>(best)] >= 0) taken[static_cast<size_t>(best)] = -2;   // claimed twice: drop both
        else if (taken[static_cast<size_t>(best)] == -1) taken[static_cast<size_t>(best)] = static_cast<int>(i);
    }
    for (size_t j = 0; j < kb.size(); ++j)
        if (taken[j] >= 0) out.emplace_back(taken[j], static_cast<int>(j));
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<ReobservationRow> reobservation_study(const Dataset& ds, const ReobservationOptions& o) {
    if (ds.pairs.size() < 2) throw InputError("the re-observation study needs at least two consecutive frames");
    for (Descriptor d : o.descriptors)
        if (!is_binary(d))
            throw InputError("the re-observation study compares binary descriptors by Hamming distance: not " +
                             descriptor_name(d));
    const auto kp = detect_dataset(ds, o.detector, o.corners);
    std::vector<std::vector<std::pair<int, int>>> tracks(ds.pairs.size() - 1);
    for (size_t k = 0; k + 1 < ds.pairs.size(); ++k)
        tracks[k] = track_corners(ds.pairs[k].left, ds.pairs[k + 1].left, kp[k].left.points, kp[k + 1].left.points, o);
    const int before = cv::getNumThreads();
    cv::setNumThreads(1);
    std::vector<ReobservationRow> rows;
    for (Descriptor d : o.descriptors) {
        ReobservationRow row;
        row.descriptor = d;
        std::mt19937_64 rng(o.seed);
        std::vector<double> same, random;
        long nearest = 0;
        Described next = describe(ds.pairs[0].left, kp[0].left.points, d, o.grid, o.detector);
        for (size_t k = 0; k + 1 < ds.pairs.size(); ++k) {
            const Described cur = std::move(next);
            next = describe(ds.pairs[k + 1].left, kp[k + 1].left.points, d, o.grid, o.detector);
            row.bits = cur.desc.cols * 8;
            std::vector<int> qi, tj;
            for (const auto& [i, j] : tracks[k]) {
                const int ri = cur.row_of[static_cast<size_t>(i)], rj = next.row_of[static_cast<size_t>(j)];
                if (ri >= 0 && rj >= 0) qi.push_back(ri), tj.push_back(rj);
            }
            if (qi.empty() || next.desc.rows < 2) continue;
            cv::Mat q(static_cast<int>(qi.size()), cur.desc.cols, CV_8U);
            for (size_t n = 0; n < qi.size(); ++n) cur.desc.row(qi[n]).copyTo(q.row(static_cast<int>(n)));
            const auto nn = landmarks::knn2(q, next.desc, cv::NORM_HAMMING);
            std::uniform_int_distribution<int> pick(0, next.desc.rows - 2);
            for (size_t n = 0; n < qi.size(); ++n) {
                same.push_back(cv::norm(q.row(static_cast<int>(n)), next.desc.row(tj[n]), cv::NORM_HAMMING) / row.bits);
                int other = pick(rng);
                if (other >= tj[n]) ++other;   // any row of frame k+1 but the re-observation
                random.push_back(cv::norm(q.row(static_cast<int>(n)), next.desc.row(other), cv::NORM_HAMMING) / row.bits);
                if (!nn[n].empty() && nn[n][0].trainIdx == tj[n]) ++nearest;
            }
            row.frames += 1;
        }
        row.reobservations = static_cast<long>(same.size());
        row.same_median = median_of(same);
        row.same_mean = mean_of(same);
        row.random_median = median_of(random);
        row.random_mean = mean_of(random);
        row.nearest = nearest;
        // the share of re-observations closer than the median random pair
        long below = 0;
        for (double s : same) below += s < row.random_median;
        row.below_random_median = below;
        rows.push_back(row);
    }
    cv::setNumThreads(before);
    return rows;
}

}  // namespace hc::landmarks
