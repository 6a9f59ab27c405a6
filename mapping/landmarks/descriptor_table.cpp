// descriptor_table.cpp: the descriptor table, the one list of the descriptors (matching.hpp):
// each row's name, help, properties and factory, and what is made from the rows.
#include <algorithm>
#include <array>
#include <stdexcept>

#include "mapping/landmarks/descriptors.hpp"
#include "mapping/landmarks/matching.hpp"
#include "model/util/table.hpp"

namespace hc::landmarks {

namespace {

cv::Ptr<cv::Feature2D> grid_thesis(const GridParams& p) {
    validate(p);
    return landmarks::GridDescriptor::create(p.g, p.h, landmarks::GridVariant::thesis);
}
cv::Ptr<cv::Feature2D> grid_corrected(const GridParams& p) {
    validate(p);
    return landmarks::GridDescriptor::create(p.g, p.h, landmarks::GridVariant::corrected);
}
cv::Ptr<cv::Feature2D> sift(const GridParams&) { return cv::SIFT::create(); }
cv::Ptr<cv::Feature2D> orb(const GridParams&) { return cv::ORB::create(); }
cv::Ptr<cv::Feature2D> brisk(const GridParams&) { return cv::BRISK::create(); }
cv::Ptr<cv::Feature2D> brief_box(const GridParams&) {
    return landmarks::BriefDescriptor::create(landmarks::BorderPolicy::drop, landmarks::BriefSmoothing::box);
}
cv::Ptr<cv::Feature2D> brief_gaussian(const GridParams&) {
    return landmarks::BriefDescriptor::create(landmarks::BorderPolicy::drop, landmarks::BriefSmoothing::gaussian);
}
cv::Ptr<cv::Feature2D> freak(const GridParams&) { return landmarks::FreakDescriptor::create(); }

const std::vector<Detector> sift_keypoints{Detector::sift, Detector::sift512};

}  // namespace

const std::vector<DescriptorInfo>& descriptor_table() {
    // id, name, help, compared, reobserved, ratio, grid, reads_octave, own_keypoints, make
    static const std::vector<DescriptorInfo> table{
        {Descriptor::grid, "grid", "the thesis's grid", true, true, 1.0, true, false, {}, grid_thesis},
        {Descriptor::grid_corrected, "grid-corrected", "the g x g grid", false, true, 1.0, true, false, {}, grid_corrected},
        {Descriptor::sift, "sift", "ratio 0.8", true, false, 0.8, false, true, sift_keypoints, sift},
        {Descriptor::sift_ratio1, "sift-ratio1", "SIFT at the grid's ratio 1", true, false, 1.0, false, true, sift_keypoints, sift},
        {Descriptor::orb, "orb", "", true, true, 1.0, false, true, {Detector::orb}, orb},
        {Descriptor::brisk, "brisk", "", true, true, 1.0, false, false, {}, brisk},
        {Descriptor::brief, "brief", "the authors' box smoothing", true, true, 1.0, false, false, {}, brief_box},
        {Descriptor::brief_gaussian, "brief-gaussian", "the paper's Gaussian", true, false, 1.0, false, false, {}, brief_gaussian},
        {Descriptor::freak, "freak", "", true, true, 1.0, false, false, {}, freak},
    };
    return table;
}

const DescriptorInfo& descriptor_info(Descriptor d) { return util::row_of(descriptor_table(), d, "a descriptor"); }

Descriptor parse_descriptor(const std::string& s) { return util::row_named(descriptor_table(), s, "descriptor"); }

std::string descriptor_name(Descriptor d) { return descriptor_info(d).name; }

std::string descriptor_list(bool with_help, bool (*keep)(const DescriptorInfo&)) {
    return util::row_names(descriptor_table(), with_help, keep);
}

std::vector<Descriptor> comparison_descriptors() {
    std::vector<Descriptor> out;
    for (const auto& r : descriptor_table())
        if (r.compared) out.push_back(r.id);
    return out;
}

std::vector<Descriptor> reobservation_descriptors() {
    std::vector<Descriptor> out;
    for (const auto& r : descriptor_table())
        if (r.reobserved) out.push_back(r.id);
    return out;
}

double default_ratio(Descriptor d) { return descriptor_info(d).ratio; }

void validate(const GridParams& p) { landmarks::check_grid_params(p.g, p.h); }

cv::Ptr<cv::Feature2D> make_descriptor(Descriptor d, const GridParams& p) { return descriptor_info(d).make(p); }

int descriptor_norm(Descriptor d) {
    // asked per pair: each row's Feature2D is made once, at the default grid parameters
    static const std::vector<int> norms = [] {
        std::vector<int> n;
        for (const auto& r : descriptor_table()) n.push_back(r.make(GridParams{})->defaultNorm());
        return n;
    }();
    const auto& t = descriptor_table();
    for (size_t i = 0; i < t.size(); ++i)
        if (t[i].id == d) return norms[i];
    throw std::logic_error("descriptor_norm: a descriptor without a row in the table");
}

bool is_binary(Descriptor d) {
    const int n = descriptor_norm(d);
    return n == cv::NORM_HAMMING || n == cv::NORM_HAMMING2;
}

std::vector<cv::KeyPoint> keypoints_for(Descriptor d, Detector det, const std::vector<cv::KeyPoint>& kp) {
    const DescriptorInfo& r = descriptor_info(d);
    const bool own = std::find(r.own_keypoints.begin(), r.own_keypoints.end(), det) != r.own_keypoints.end();
    if (!r.reads_octave || own) return kp;
    std::vector<cv::KeyPoint> out = kp;
    for (auto& k : out) k.octave = 0;
    return out;
}

}  // namespace hc::landmarks
