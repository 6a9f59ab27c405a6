// pipeline.cpp: descriptors, stereo matching and scoring of a pair, landmarks of a frame,
// the descriptor comparison and the g x h study of the grid descriptor.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>

#include <opencv2/core/utility.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "mapping/landmarks/descriptors.hpp"
#include "mapping/landmarks/pipeline.hpp"

namespace hc::landmarks {

// ---- descriptors (the table: descriptor_table.cpp) ---------------------------------

Norm parse_norm(const std::string& s) {
    if (s == "auto") return Norm::automatic;
    if (s == "hamming") return Norm::hamming;
    if (s == "l2") return Norm::l2;
    throw InputError("unknown matcher norm '" + s + "' (auto, hamming or l2)");
}

namespace {

int cv_norm(Descriptor d, Norm n) {
    if (n == Norm::automatic) return descriptor_norm(d);
    return n == Norm::hamming ? cv::NORM_HAMMING : cv::NORM_L2;
}

}  // namespace

void check_combination(Descriptor d, Detector, Norm n) {
    if (n == Norm::automatic) return;
    if (!is_binary(d) && n == Norm::hamming)
        throw InputError("descriptor " + descriptor_name(d) + " is a float vector: it cannot be matched with the Hamming norm");
    if (is_binary(d) && n == Norm::l2)
        throw InputError("descriptor " + descriptor_name(d) + " is binary: it cannot be matched with the L2 norm");
}

// ---- one pair ---------------------------------------------------------------------------

long PairResult::correct() const {
    return std::count_if(matches.begin(), matches.end(), [](const StereoMatch& m) { return m.epipolar; });
}
long PairResult::truth_known() const {
    return std::count_if(matches.begin(), matches.end(), [](const StereoMatch& m) { return m.epipolar && m.truth >= 0; });
}
long PairResult::truth_correct() const {
    return std::count_if(matches.begin(), matches.end(),
                         [](const StereoMatch& m) { return m.epipolar && m.truth == truth_right; });
}
long PairResult::truth_correct_x() const {
    return std::count_if(matches.begin(), matches.end(), [](const StereoMatch& m) {
        return m.epipolar && (m.truth == truth_right || m.truth == truth_x_only);
    });
}

namespace {

landmarks::MatchOptions match_options(Descriptor d, const MatchParams& mp) {
    landmarks::MatchOptions o;
    o.norm = cv_norm(d, mp.norm);
    o.symmetry = true;
    o.ratio = mp.drop_ties ? landmarks::RatioTest::drop_ties : landmarks::RatioTest::printed;
    o.max_ratio = mp.ratio > 0 ? mp.ratio : default_ratio(d);
    o.epipolar = false;   // scored here: matches failing it still count as "all"
    return o;
}

/// Matches of described keypoints, scored by the epipolar test and the ground truth.
void score(const std::vector<cv::DMatch>& dm, const std::vector<cv::KeyPoint>& kl, const std::vector<cv::KeyPoint>& kr,
           const MatchParams& mp, const cv::Mat& disparity, std::vector<StereoMatch>& out) {
    out.clear();
    out.reserve(dm.size());
    for (const auto& m : dm) {
        StereoMatch s;
        s.left_index = m.queryIdx;
        s.right_index = m.trainIdx;
        s.left = kl[static_cast<size_t>(m.queryIdx)].pt;
        s.right = kr[static_cast<size_t>(m.trainIdx)].pt;
        s.distance = m.distance;
        s.epipolar = std::abs(s.right.y - s.left.y) < mp.epipolar_px;
        if (!disparity.empty()) {
            const int x = static_cast<int>(std::lround(s.left.x)), y = static_cast<int>(std::lround(s.left.y));
            const float d = x >= 0 && y >= 0 && x < disparity.cols && y < disparity.rows ? disparity.at<float>(y, x) : 0.f;
            if (d > 0) {
                const bool x_ok = std::abs(s.left.x - s.right.x - d) <= 1.0f;
                s.truth = !x_ok ? truth_wrong : std::abs(s.right.y - s.left.y) <= 1.0f ? truth_right : truth_x_only;
            }
        }
        out.push_back(s);
    }
}

std::vector<cv::DMatch> run_matcher(const cv::Mat& dl, const std::vector<cv::KeyPoint>& kl, const cv::Mat& dr,
                                    const std::vector<cv::KeyPoint>& kr, const landmarks::MatchOptions& o) {
    if (dl.empty() || dr.empty()) return {};   // no keypoints on a side: no matches
    return landmarks::match_stereo(dl, kl, dr, kr, o);
}

}  // namespace

namespace {

/// Keypoints moved to their rectified positions (landmarks::rectify_points), the rest kept.
void rectify(std::vector<cv::KeyPoint>& kp, const landmarks::Calibration& rig, landmarks::Side side) {
    std::vector<cv::Point2f> pts;
    pts.reserve(kp.size());
    for (const auto& k : kp) pts.push_back(k.pt);
    const auto rect = landmarks::rectify_points(rig, side, pts);
    for (size_t i = 0; i < kp.size(); ++i) kp[i].pt = rect[i];
}

}  // namespace

PairResult match_pair(const StereoImages& img, const PairKeypoints& kp, Descriptor d, const GridParams& gp,
                      const MatchParams& mp, const cv::Mat& disparity, const landmarks::Calibration* rig) {
    check_combination(d, kp.left.source, mp.norm);
    if (img.left.size() != img.right.size()) throw InputError("pair '" + img.name + "': images differ in size");
    if (!disparity.empty() && disparity.size() != img.left.size())
        throw InputError("pair '" + img.name + "': the ground-truth disparity differs in size from the left image");
    auto desc = make_descriptor(d, gp);
    PairResult r;
    r.name = img.name;
    r.kp_left = keypoints_for(d, kp.left.source, kp.left.points);
    r.kp_right = keypoints_for(d, kp.right.source, kp.right.points);
    const auto opts = match_options(d, mp);
    // the grid reads positions only: described at the rectified ones; the others read the raw image
    const bool positions_only = descriptor_info(d).grid;
    cv::Mat dr;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<cv::DMatch> dm;
    try {
        if (rig && positions_only) {
            rectify(r.kp_left, *rig, landmarks::Side::left);
            rectify(r.kp_right, *rig, landmarks::Side::right);
        }
        desc->compute(img.left, r.kp_left, r.desc_left);
        desc->compute(img.right, r.kp_right, dr);
        if (rig && !positions_only) {   // the survivors of the descriptor's border
            rectify(r.kp_left, *rig, landmarks::Side::left);
            rectify(r.kp_right, *rig, landmarks::Side::right);
        }
        dm = run_matcher(r.desc_left, r.kp_left, dr, r.kp_right, opts);
    } catch (const hc::InputError& e) {
        throw InputError("pair '" + img.name + "', " + descriptor_name(d) + ": " + e.what());
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.descriptor_bytes = desc->descriptorSize() * (desc->descriptorType() == CV_32F ? 4 : 1);
    r.keypoints_left = static_cast<int>(r.kp_left.size());
    r.keypoints_right = static_cast<int>(r.kp_right.size());
    r.has_truth = !disparity.empty();
    score(dm, r.kp_left, r.kp_right, mp, disparity, r.matches);
    return r;
}

// ---- landmarks ----------------------------------------------------------------------------

std::vector<Landmark> landmarks_from(const PairResult& r, const landmarks::RectifiedRig& calib, const PipelineOptions& o) {
    std::vector<Landmark> out;
    const size_t row_bytes = r.desc_left.empty() ? 0 : r.desc_left.cols * r.desc_left.elemSize();
    for (const auto& m : r.matches) {
        if (!m.epipolar) continue;
        const landmarks::Point3 t = landmarks::triangulate(calib, pixels(m.left, m.right), o.noise);
        const double D = m.left.x - m.right.x - (calib.cx0 - calib.cx1);
        if (!t.valid || D < o.min_disparity) continue;
        Landmark l;
        l.p_cam = cv::Vec3d(t.p[0], t.p[1], t.p[2]);
        l.cov = cv::Matx33d(&t.cov[0][0]);
        l.left = m.left;
        l.right = m.right;
        l.match_distance = m.distance;
        const std::uint8_t* row = r.desc_left.ptr<std::uint8_t>(m.left_index);
        l.descriptor.assign(row, row + row_bytes);
        out.push_back(std::move(l));
    }
    return out;
}

std::vector<Landmark> acquire(const cv::Mat& left, const cv::Mat& right, const landmarks::RectifiedRig& calib,
                              const PipelineOptions& o) {
    calib.validate();
    const StereoImages img{left, right, "frame"};
    const auto kp = detect_pairs(o.detector, {img}, o.corners);
    return landmarks_from(match_pair(img, kp.at(0), o.descriptor, o.grid, o.match), calib, o);
}

std::vector<std::vector<Landmark>> acquire_dataset(const Dataset& ds, const PipelineOptions& o) {
    for (const auto& c : ds.calib) c.validate();
    return acquire_dataset(ds, detect_dataset(ds, o.detector, o.corners), o);
}

std::vector<std::vector<Landmark>> acquire_dataset(const Dataset& ds, const std::vector<PairKeypoints>& kp,
                                                   const PipelineOptions& o) {
    for (const auto& c : ds.calib) c.validate();
    if (kp.size() != ds.pairs.size())
        throw InputError("corners of " + std::to_string(kp.size()) + " pairs given for a dataset of " +
                         std::to_string(ds.pairs.size()) + " pairs");
    std::vector<std::vector<Landmark>> out;
    out.reserve(ds.pairs.size());
    for (size_t i = 0; i < ds.pairs.size(); ++i) {
        const cv::Mat truth = i < ds.disparity.size() ? ds.disparity[i] : cv::Mat();
        out.push_back(landmarks_from(match_pair(ds.pairs[i], kp.at(i), o.descriptor, o.grid, o.match, truth, ds.rig.get()),
                                     ds.calib.at(i), o));
    }
    return out;
}

// ---- comparison and study -------------------------------------------------------------------

void Totals::add(const PairResult& r) {
    all += r.all();
    correct += r.correct();
    truth_known += r.truth_known();
    truth_correct += r.truth_correct();
    truth_correct_x += r.truth_correct_x();
    keypoints += r.keypoints_left + r.keypoints_right;
    seconds += r.seconds;
    ++pairs;
}

std::vector<PairKeypoints> detect_dataset(const Dataset& ds, Detector d, const CornerOptions& co) {
    if (!is_hardware(d)) return detect_pairs(d, ds.pairs, co);
    bool one_size = true;
    for (const auto& p : ds.pairs) one_size = one_size && p.left.size() == ds.pairs.at(0).left.size();
    if (one_size) return detect_pairs(d, ds.pairs, co);
    std::vector<PairKeypoints> out;
    for (size_t k = 0; k < ds.pairs.size(); ++k) {
        auto one = detect_pairs(d, {ds.pairs[k]}, co).at(0);
        one.left.frame = static_cast<int>(2 * k);
        one.right.frame = static_cast<int>(2 * k + 1);
        out.push_back(std::move(one));
    }
    return out;
}

namespace {

const cv::Mat& truth_of(const Dataset& ds, size_t k) {
    static const cv::Mat none;
    return k < ds.disparity.size() ? ds.disparity[k] : none;
}

/// Runs `fn` with OpenCV on one thread, restoring the previous count.
template <class F>
auto one_thread(F&& fn) {
    const int before = cv::getNumThreads();
    cv::setNumThreads(1);
    struct Restore {
        int n;
        ~Restore() { cv::setNumThreads(n); }
    } restore{before};
    return fn();
}

}  // namespace

std::vector<ComparisonRow> compare(const Dataset& ds, const ComparisonOptions& o,
                                   std::vector<std::vector<PairKeypoints>>* keypoints) {
    std::vector<ComparisonRow> rows;
    if (keypoints) keypoints->clear();
    for (Detector det : o.detectors) {
        const auto kp = detect_dataset(ds, det, o.corners);
        if (keypoints) keypoints->push_back(kp);
        std::vector<ComparisonRow> drows(o.descriptors.size());
        for (size_t i = 0; i < drows.size(); ++i) {
            check_combination(o.descriptors[i], det, o.match.norm);
            drows[i].descriptor = o.descriptors[i];
            drows[i].detector = det;
            drows[i].grid = o.grid;
            drows[i].pairs.resize(ds.pairs.size());
        }
        // every (descriptor, pair) is one task on one thread (OpenCV inside it on one thread
        // too), so each pair's time is a one-thread time whatever the number of workers
        const size_t n = ds.pairs.size();
        tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
        one_thread([&] {
            arena.execute([&] {
                tbb::parallel_for(size_t{0}, drows.size() * n, [&](size_t t) {
                    const size_t i = t / n, k = t % n;
                    drows[i].pairs[k] =
                        match_pair(ds.pairs[k], kp[k], drows[i].descriptor, o.grid, o.match, truth_of(ds, k), ds.rig.get());
                });
            });
            return 0;
        });
        for (auto& row : drows) {
            for (const auto& pr : row.pairs) row.totals.add(pr);
            row.descriptor_bytes = row.pairs.empty() ? 0 : row.pairs.front().descriptor_bytes;
            if (o.progress)
                o.progress(detector_name(det) + " x " + descriptor_name(row.descriptor) + ": " +
                           std::to_string(row.totals.correct) + " correct of " + std::to_string(row.totals.all));
            rows.push_back(std::move(row));
        }
    }
    return rows;
}

StudyCell StudyResult::best_correct() const {
    StudyCell b;
    for (const auto& c : cells)
        if (c.correct > b.correct) b = c;
    return b;
}

StudyCell StudyResult::best_truth() const {
    StudyCell b;
    for (const auto& c : cells)
        if (c.truth_correct > b.truth_correct) b = c;
    return b;
}

StudyResult StudyResult::on_pairs(const std::vector<size_t>& pairs) const {
    StudyResult r;
    r.detector = detector;
    for (const auto& c : cells) {
        StudyCell sub{c.g, c.h, 0, 0, 0, 0, {}, {}};
        for (size_t k : pairs) {
            if (k >= c.pair_correct.size()) throw std::out_of_range("StudyResult::on_pairs: no such pair");
            sub.correct += c.pair_correct[k];
            sub.truth_correct += c.pair_truth_correct[k];
            sub.pair_correct.push_back(c.pair_correct[k]);
            sub.pair_truth_correct.push_back(c.pair_truth_correct[k]);
        }
        r.cells.push_back(std::move(sub));
    }
    return r;
}

HeldOutChoice held_out_choice(const StudyResult& s, const std::vector<size_t>& choose, const std::vector<size_t>& report,
                              bool by_truth) {
    const StudyResult a = s.on_pairs(choose), b = s.on_pairs(report);
    HeldOutChoice h;
    h.chosen = by_truth ? a.best_truth() : a.best_correct();
    for (const auto& c : b.cells)
        if (c.g == h.chosen.g && c.h == h.chosen.h) h.on_report = c;
    h.report_best = by_truth ? b.best_truth() : b.best_correct();
    return h;
}

StudyResult study(const Dataset& ds, Detector d, const StudyOptions& o) {
    return study(ds, d, detect_dataset(ds, d, o.corners), o);
}

StudyResult study(const Dataset& ds, Detector d, const std::vector<PairKeypoints>& kp, const StudyOptions& o) {
    if (kp.size() != ds.pairs.size()) throw std::invalid_argument("study: one keypoint pair per dataset pair");
    validate(GridParams{o.g_min, o.h_min});
    validate(GridParams{o.g_max, o.h_max});
    if (o.g_max < o.g_min || o.h_max < o.h_min) throw InputError("study: empty g or h range");
    StudyResult res;
    res.detector = d;
    for (int g = o.g_min; g <= o.g_max; ++g)
        for (int h = o.h_min; h <= o.h_max; ++h) res.cells.push_back(StudyCell{g, h, 0, 0, 0, 0, {}, {}});
    const Descriptor desc = o.corrected ? Descriptor::grid_corrected : Descriptor::grid;
    tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
    const int before = cv::getNumThreads();
    cv::setNumThreads(1);   // cells run in parallel; OpenCV inside each on one thread
    arena.execute([&] {
        tbb::parallel_for(size_t{0}, res.cells.size(), [&](size_t i) {
            StudyCell& c = res.cells[i];
            for (size_t k = 0; k < ds.pairs.size(); ++k) {
                const PairResult r =
                    match_pair(ds.pairs[k], kp[k], desc, GridParams{c.g, c.h}, o.match, truth_of(ds, k), ds.rig.get());
                c.all += r.all();
                c.correct += r.correct();
                c.truth_correct += r.truth_correct();
                c.truth_correct_x += r.truth_correct_x();
                c.pair_correct.push_back(r.correct());
                c.pair_truth_correct.push_back(r.truth_correct());
            }
        });
    });
    cv::setNumThreads(before);
    return res;
}

Totals score_formats(const Dataset& ds, const Formats& formats, Detector source, const GridParams& gp,
                     const MatchParams& mp) {
    if (!is_hardware(source)) throw InputError("score_formats: the source must be spec, cycle or rtl");
    CornerOptions co;
    co.formats = formats;
    const auto kp = detect_dataset(ds, source, co);
    Totals t;
    for (size_t k = 0; k < ds.pairs.size(); ++k)
        t.add(match_pair(ds.pairs[k], kp[k], Descriptor::grid, gp, mp, truth_of(ds, k), ds.rig.get()));
    return t;
}

}  // namespace hc::landmarks
