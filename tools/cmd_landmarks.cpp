// cmd_landmarks.cpp: the flags of `harris-cosim landmarks` (mapping/landmarks/landmarks_command.hpp):
// descriptor, stereo matching, scoring, triangulation, the descriptor comparison and the
// grid's g x h study (docs/landmarks.md).
#include "mapping/landmarks/landmarks.hpp"
#include "mapping/landmarks/landmarks_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_landmarks_command(CLI::App& app) {
    const auto [cmd, o] = add_command<Sharded<landmarks::LandmarksCommand>>(app,
        "landmarks", "corners -> descriptor -> stereo matches -> 3D landmarks, scored against ground truth (thesis 6.4)");
    cmd->add_option("--corners", o->corners, "corner sources, comma-separated: " + landmarks::detector_list(true))
        ->capture_default_str();
    cmd->add_option("--descriptor", o->descriptor, "descriptors, comma-separated: " + landmarks::descriptor_list(true))
        ->capture_default_str();
    cmd->add_option("--g", o->g, "grid side")->capture_default_str();
    cmd->add_option("--h", o->h, "grid resolution reduction 2^h")->capture_default_str();
    cmd->add_option("--norm", o->norm, "matcher norm: auto (the descriptor's), hamming or l2")->capture_default_str();
    cmd->add_option("--ratio", o->ratio, "2-NN ratio for every descriptor (0: by descriptor: 0.8 for sift, the thesis's SIFT reference after Lowe; 1 for the others)");
    cmd->add_flag("--drop-ties", o->drop_ties, "ratio test also drops d0 == d1 (the evidently intended test)");
    cmd->add_flag("--compare", o->compare, "the thesis's comparison: detectors " + landmarks::detector_names(landmarks::ComparisonOptions{}.detectors) +
                  " x the descriptors " + landmarks::descriptor_list(false, +[](const landmarks::DescriptorInfo& r) { return r.compared; }));
    cmd->add_flag("--study", o->study, "g x h study of the grid descriptor (g 4..32, h 0..5) on each detector's corners");
    cmd->add_flag("--reobservation", o->reobservation,
                  "how descriptors change between consecutive frames: corners tracked by optical flow from each left "
                  "image to the next, Hamming distance of re-observations against random pairs (default descriptors: " +
                  landmarks::descriptor_list(false, +[](const landmarks::DescriptorInfo& r) { return r.reobserved; }) + ")");
    cmd->add_flag("--corrected", o->corrected, "study the corrected g x g grid instead of the thesis's");
    cmd->add_option("--dataset", o->source.dataset, "middlebury or kitti")->capture_default_str();
    cmd->add_option("--middlebury", o->source.middlebury, "Middlebury 2006 folder of scenes, or one scene (default: <data>/middlebury2006/half)");
    cmd->add_flag("!--no-truth", o->source.need_truth, "accept Middlebury scenes without disp1.png (e.g. third/): no ground-truth scoring");
    cmd->add_option("--kitti", o->source.kitti, "KITTI odometry root holding sequences/ (default: <data>/kitti)");
    cmd->add_option("--sequence", o->source.sequence, "KITTI sequence")->capture_default_str();
    add_pair_range_option(cmd, o->source.pairs, "; --dataset kitti, default " + o->source.pairs);
    add_rig_options(cmd, o->source.rig,
                    "run on its unrectified pairs --left/--right, keypoints undistorted and rectified (cv::undistortPoints)");
    cmd->add_option("--data", o->source.data, "data directory (else $HARRIS_COSIM_DATA, else the build default)");
    cmd->add_option("--config", o->config, "formats JSON of the co-processor (spec, cycle, rtl corners)");
    cmd->add_option("--sigma", o->sigma, "corner localisation noise: standard deviation (px) of each of x_l, y_l, x_r, y_r, independent, "
                    "in the landmark covariance (an assumed value; integer rounding alone would be 1/sqrt(12) = 0.29 px)")->capture_default_str();
    cmd->add_option("--overlays", o->overlays, "match overlay PNGs per row (first N pairs)")->capture_default_str();
    cmd->add_flag("!--no-landmark-files", o->landmark_files, "skip the per-pair landmark CSV/PLY files");
    cmd->add_option("--threads", o->threads,
                    "worker threads of the comparison and the study (0: all cores); each pair's extraction and matching "
                    "runs on one thread either way");
    cmd->add_option("--out", o->out, "output directory")->capture_default_str();
    add_runner_flags(cmd, o->runner);
    cmd->callback([o, cmd] {
        o->descriptor_given = cmd->count("--descriptor") > 0;
        landmarks::run_landmarks_command(*o, job_runner(cmd, o->runner));
    });
}

}  // namespace hc::tools
