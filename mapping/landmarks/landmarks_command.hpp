// landmarks_command.hpp: `harris-cosim landmarks` as the command line hands it over: the
// descriptor comparison on a dataset (in one process or in shards), with the grid's g x h
// study and the landmark files, or the re-observation study (landmarks.hpp).
#pragma once

#include <string>

#include "io/cluster/runner.hpp"
#include "mapping/landmarks/datasets.hpp"

namespace hc::landmarks {

/// The command's settings, one field per flag.
struct LandmarksCommand {
    std::string corners = "opencv", descriptor = "grid", norm = "auto", config, out = "landmarks-report";
    DatasetChoice source;   ///< --calib, --left, --right, --dataset, --middlebury, --kitti, --data, --sequence, --pairs
    int g = 16, h = 3, overlays = 2, threads = 0;
    double ratio = 0, sigma = 0.5;
    bool drop_ties = false, compare = false, study = false, corrected = false, landmark_files = true;
    bool reobservation = false;
    bool descriptor_given = false;   ///< --descriptor was given (the re-observation study has its own default list)
};

/// Runs the comparison (or the re-observation study), writes its report into c.out and prints
/// its table. InputError for bad input.
void run_landmarks_command(const LandmarksCommand& c, const cluster::JobRunner& runner);

}  // namespace hc::landmarks
