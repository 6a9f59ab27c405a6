// landmarks_job.hpp: the job kind "landmarks" of hc::cluster, the descriptor comparison in
// shards (landmarks_job.cpp): a shard computes, for one detector and a range of the
// dataset's pairs, every descriptor's matches (match_pair). Hardware detectors carry state
// from pair to pair, so their shards span the whole dataset.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/cluster/cluster.hpp"
#include "mapping/landmarks/pipeline.hpp"

namespace hc::landmarks {

struct LandmarksJob {
    std::string dataset = "middlebury";   ///< middlebury or kitti
    std::filesystem::path root;           ///< Middlebury folder of scenes, or the KITTI root
    bool need_truth = true;               ///< Middlebury: require disp1.png
    std::string sequence = "01";          ///< KITTI
    int first = 0, last = 0;              ///< KITTI stereo pairs [first, last)
    ComparisonOptions options;            ///< detectors, descriptors, grid, match, corners
    std::size_t pairs = 0;                ///< pairs of the dataset (to split them)
    int shards = 0;                       ///< 0: one per detector and pair
};
/// InputError (landmarks') for an impossible detector/descriptor combination.
cluster::Manifest landmarks_manifest(const LandmarksJob& p);
/// The rows of the comparison (detectors x descriptors, in the options' order), each pair's
/// result as match_pair returned it (its time included).
std::vector<ComparisonRow> landmarks_rows(const nlohmann::json& merged);
/// Adds the kind "landmarks" to `r`.
void add_landmarks_job(cluster::JobRegistry& r);

}  // namespace hc::landmarks
