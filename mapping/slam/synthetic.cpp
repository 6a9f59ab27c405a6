// synthetic.cpp: noisy odometry on a true trajectory, the synthetic rig and the synthetic
// stereo landmarks along a trajectory.
#include "mapping/slam/synthetic.hpp"

#include <cmath>

namespace hc::slam {

Mat3 SyntheticOdometry::covariance() const {
    return Eigen::Vector3d(sigma_dx * sigma_dx, sigma_dy * sigma_dy, sigma_dtheta * sigma_dtheta).asDiagonal();
}

void SyntheticOdometry::validate() const {
    if (!(sigma_dx > 0) || !(sigma_dy > 0) || !(sigma_dtheta > 0))
        throw InputError("the synthetic odometry noise (--sigma-dx, --sigma-dy, --sigma-dtheta) must be positive");
}

std::vector<Motion> noisy_odometry(const std::vector<Pose>& truth, const SyntheticOdometry& model, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Motion> u;
    for (size_t k = 1; k < truth.size(); ++k) {
        const Motion e = between(truth[k - 1], truth[k]);
        const double nx = g(rng), ny = g(rng), nt = g(rng);
        u.emplace_back(e(0) + model.sigma_dx * nx, e(1) + model.sigma_dy * ny, e(2) + model.sigma_dtheta * nt);
    }
    return u;
}

landmarks::RectifiedRig synthetic_rig() {
    const double fx = 718.856, baseline = 0.5372;
    landmarks::RectifiedRig r;
    r.fx = r.fy = fx;
    r.cx0 = r.cx1 = 607.1928;
    r.cy = 185.2157;
    r.tx1 = -fx * baseline;
    r.width = 1241;
    r.height = 376;
    return r;
}

SyntheticFrames::SyntheticFrames(std::vector<Mat34> poses, const landmarks::RectifiedRig& rig,
                                 const landmarks::PixelNoise& noise, int count, int flip_bits, uint64_t seed)
    : poses_(std::move(poses)), rig_(rig), noise_(noise), flip_bits_(flip_bits), rng_(seed) {
    if (poses_.empty()) throw InputError("synthetic landmarks need at least one pose");
    if (rig.width < 1 || rig.height < 1) throw InputError("synthetic landmarks need a rig with an image size");
    if (count < 1) throw InputError("the synthetic world is empty: the landmark count must be at least 1");
    std::uniform_int_distribution<int> pick(0, static_cast<int>(poses_.size()) - 1), byte(0, 255);
    std::uniform_real_distribution<double> lateral(4, 30), forward(0, 40), height(-3, 1), side(0, 1);
    for (int i = 0; i < count; ++i) {
        const Mat34& T = poses_[pick(rng_)];
        const double s = side(rng_) < 0.5 ? -1 : 1;
        const Eigen::Vector3d pc(s * lateral(rng_), height(rng_), forward(rng_));
        world_.push_back(T.leftCols<3>() * pc + T.col(3));
        std::vector<uint8_t> d(32);
        for (auto& b : d) b = static_cast<uint8_t>(byte(rng_));
        desc_.push_back(std::move(d));
    }
}

bool SyntheticFrames::next(StereoFrame& f) {
    if (next_ >= poses_.size()) return false;
    const Mat34& T = poses_[next_++];
    std::uniform_int_distribution<int> bit(0, 255);
    f.clear();
    const Eigen::Matrix3d Rt = T.leftCols<3>().transpose();
    for (size_t i = 0; i < world_.size(); ++i) {
        const Eigen::Vector3d p = Rt * (world_[i] - T.col(3));
        if (p.z() < 2 || p.z() > 60) continue;
        const double q[3] = {p.x(), p.y(), p.z()};
        const landmarks::StereoPixels m = landmarks::project(rig_, q);
        if (m.u_l < 0 || m.u_l >= rig_.width || m.u_r < 0 || m.v_l < 0 || m.v_l >= rig_.height) continue;
        const landmarks::StereoPixels n = noise_.perturb(m, rng_);
        if (n.u_l - n.u_r < 1) continue;
        StereoLandmarkObs o = to_observation(landmarks::triangulate(rig_, n, noise_));
        o.descriptor = desc_[i];
        o.id_hint = static_cast<int>(i);
        for (int b = 0; b < flip_bits_; ++b) {
            const int k = bit(rng_);
            o.descriptor[static_cast<size_t>(k / 8)] ^= static_cast<uint8_t>(1u << (k % 8));
        }
        f.push_back(std::move(o));
    }
    return true;
}

std::vector<StereoFrame> synthesize_stereo_frames(const std::vector<Mat34>& poses, const landmarks::RectifiedRig& rig,
                                                  const landmarks::PixelNoise& noise, int count, int flip_bits,
                                                  uint64_t seed) {
    SyntheticFrames source(poses, rig, noise, count, flip_bits, seed);
    std::vector<StereoFrame> frames;
    StereoFrame f;
    while (source.next(f)) frames.push_back(std::move(f));
    return frames;
}

}  // namespace hc::slam
