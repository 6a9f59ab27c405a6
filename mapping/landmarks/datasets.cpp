// datasets.cpp: Middlebury 2006 scenes and KITTI odometry pairs as stereo datasets, with
// ground-truth disparity (Middlebury) and the rectified rig of each pair.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/frames/frames.hpp"
#include "mapping/landmarks/calib.hpp"
#include "mapping/landmarks/datasets.hpp"
#include "mapping/landmarks/geometry.hpp"

namespace fs = std::filesystem;

namespace hc::landmarks {

namespace {

cv::Mat read_grey(const fs::path& p) {
    if (!fs::exists(p)) throw InputError("'" + p.string() + "' does not exist");
    cv::Mat m = cv::imread(p.string(), cv::IMREAD_GRAYSCALE);
    if (m.empty()) throw InputError("'" + p.string() + "' is not a readable image");
    return m;
}

}  // namespace

// The 2006 datasets come in full (1110 rows), half (555) and third (370) size; the
// disparity PNGs of the reduced sizes hold the disparity in the reduced image's pixels
// multiplied by the reduction factor (2 or 3), i.e. value = d * (1/scale), 0 = unknown.
// Pinned by tests/landmarks/data_test.cpp on pixels checked against the images.
float middlebury_disparity(std::uint8_t value, double scale) {
    return value == 0 ? 0.f : static_cast<float>(value * scale);
}

double middlebury_scale(int height) {
    if (height == 1110) return 1.0;
    if (height == 555) return 0.5;
    if (height == 370) return 1.0 / 3.0;
    throw InputError("a Middlebury 2006 image has 1110, 555 or 370 rows, not " + std::to_string(height));
}

MiddleburyScene load_middlebury(const fs::path& dir, bool need_truth) {
    if (!fs::is_directory(dir)) throw InputError("Middlebury scene '" + dir.string() + "' is not a directory");
    MiddleburyScene s;
    s.name = dir.filename().string();
    s.images.name = s.name;
    s.images.left = read_grey(dir / "view1.png");
    s.images.right = read_grey(dir / "view5.png");
    if (s.images.left.size() != s.images.right.size())
        throw InputError("Middlebury scene '" + dir.string() + "': view1.png and view5.png differ in size");
    s.scale = middlebury_scale(s.images.left.rows);
    const fs::path disp = dir / "disp1.png";
    if (need_truth && fs::exists(disp)) {
        cv::Mat d = cv::imread(disp.string(), cv::IMREAD_UNCHANGED);
        if (d.empty() || d.type() != CV_8UC1) throw InputError("'" + disp.string() + "' is not an 8-bit grey disparity PNG");
        if (d.size() != s.images.left.size())
            throw InputError("'" + disp.string() + "' differs in size from view1.png");
        s.disparity.create(d.size(), CV_32F);
        for (int r = 0; r < d.rows; ++r)
            for (int c = 0; c < d.cols; ++c) s.disparity.at<float>(r, c) = middlebury_disparity(d.at<std::uint8_t>(r, c), s.scale);
    } else if (need_truth) {
        throw InputError("Middlebury scene '" + dir.string() + "' has no disp1.png (the ground truth the scoring needs)");
    }
    std::ifstream dm(dir / "dmin.txt");
    if (dm && !(dm >> s.dmin_full)) throw InputError("'" + (dir / "dmin.txt").string() + "' holds no number");
    return s;
}

std::vector<fs::path> middlebury_scenes(const fs::path& root) {
    std::vector<fs::path> v;
    if (!fs::is_directory(root)) throw InputError("Middlebury folder '" + root.string() + "' is not a directory");
    if (fs::exists(root / "view1.png")) return {root};
    for (const auto& e : fs::directory_iterator(root))
        if (e.is_directory() && fs::exists(e.path() / "view1.png")) v.push_back(e.path());
    std::sort(v.begin(), v.end());
    if (v.empty()) throw InputError("Middlebury folder '" + root.string() + "' holds no scene (a folder with view1.png)");
    return v;
}

Dataset middlebury_dataset(const fs::path& root, bool need_truth) {
    Dataset ds;
    ds.name = "middlebury-" + root.filename().string();
    for (const auto& dir : middlebury_scenes(root)) {
        MiddleburyScene s = load_middlebury(dir, need_truth);
        ds.calib.push_back(middlebury_calib(s.scale, s.dmin_full, s.images.left.size()));
        ds.pairs.push_back(std::move(s.images));
        ds.disparity.push_back(std::move(s.disparity));
    }
    return ds;
}

// ---- KITTI ----------------------------------------------------------------------------

Dataset kitti_dataset(const fs::path& kitti_root, const std::string& sequence, util::Range pairs, const std::string& what) {
    // the layout (folders, file names, calib.txt) and the rule for a pair range are hc::frames's
    if (!frames::is_kitti_sequence(kitti_root, sequence))
        throw InputError("'" + frames::kitti_sequence_dir(kitti_root, sequence).string() +
                         "' is not a KITTI odometry sequence (image_0/, image_1/)");
    const frames::KittiSequence seq = frames::open_kitti(kitti_root, sequence);
    const std::vector<fs::path> paths = frames::stereo_stream(seq, pairs, what);
    const landmarks::RectifiedRig calib = landmarks::read_kitti_calib(seq.calib_txt()).rectified;
    Dataset ds;
    ds.name = "kitti-" + sequence;
    for (std::size_t i = 0; i + 1 < paths.size(); i += 2) {
        const fs::path &l = paths[i], &r = paths[i + 1];
        StereoImages p{read_grey(l), read_grey(r), sequence + "/" + l.stem().string()};
        if (p.left.size() != p.right.size())
            throw InputError("KITTI pair '" + l.string() + "': left and right images differ in size");
        ds.pairs.push_back(std::move(p));
        ds.disparity.emplace_back();
        ds.calib.push_back(calib);
    }
    return ds;
}

// ---- a user's own rig ---------------------------------------------------------------------

landmarks::Calibration read_rig_calibration(const fs::path& file) {
    const std::string ext = file.extension().string();
    if (ext == ".yml" || ext == ".yaml" || ext == ".json") return landmarks::read_opencv_storage(file);
    return landmarks::read_kitti_calib(file);
}

Dataset rig_dataset(const std::vector<fs::path>& left, const std::vector<fs::path>& right, const landmarks::Calibration& rig) {
    if (left.empty()) throw InputError("a rig's stereo pairs: no left image");
    if (left.size() != right.size())
        throw InputError("a rig's stereo pairs: " + std::to_string(left.size()) + " left images but " +
                         std::to_string(right.size()) + " right images");
    Dataset ds;
    ds.name = "rig";
    ds.rig = std::make_shared<const landmarks::Calibration>(rig);
    const cv::Size size = landmarks::image_size(rig);
    for (size_t k = 0; k < left.size(); ++k) {
        StereoImages p{read_grey(left[k]), read_grey(right[k]), left[k].stem().string() + "+" + right[k].stem().string()};
        for (const auto& [img, file] : {std::pair{&p.left, &left[k]}, std::pair{&p.right, &right[k]}})
            if (!size.empty() && img->size() != size)
                throw InputError("'" + file->string() + "' is " + std::to_string(img->cols) + "x" + std::to_string(img->rows) +
                                 ", the calibration's images " + std::to_string(size.width) + "x" +
                                 std::to_string(size.height));
        if (p.left.size() != p.right.size())
            throw InputError("'" + left[k].string() + "' and '" + right[k].string() + "' differ in size");
        ds.pairs.push_back(std::move(p));
        ds.disparity.emplace_back();
        ds.calib.push_back(rig.rectified);
    }
    return ds;
}

Dataset open_dataset(const DatasetChoice& c, fs::path& root) {
    if (c.rig.given()) {
        const frames::RigPairs rig = frames::open_rig(c.rig);
        return rig_dataset(rig.left, rig.right, read_rig_calibration(rig.calib));
    }
    const auto data = frames::data_dir(c.data);
    if (c.dataset == "middlebury") {
        root = c.middlebury;
        if (root.empty()) {
            if (!data) throw InputError("no --middlebury folder and no data directory (--data, $HARRIS_COSIM_DATA)");
            root = *data / "middlebury2006" / "half";
        }
        return middlebury_dataset(root, c.need_truth);
    }
    if (c.dataset == "kitti") {
        root = frames::require_kitti_root(c.kitti, c.data, "--dataset kitti needs KITTI data");
        return kitti_dataset(root, c.sequence, util::parse_range(c.pairs, "--pairs"), "--pairs " + c.pairs);
    }
    throw InputError("--dataset '" + c.dataset + "' (middlebury or kitti)");
}

}  // namespace hc::landmarks
