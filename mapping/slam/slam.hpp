// slam.hpp: 2-D top-view EKF-SLAM (the thesis's section 2.5 and 5.4, a port of the
// structure of J. Solà's EKF-SLAM course code, "Simultaneous localization and mapping with
// the extended Kalman filter", 2013/2014), with its simulator, its consistency measures
// (NEES against chi-square bounds) and the stereo-landmark front end for KITTI sequences.
//
// The library's one public header: it includes its parts, each its own header (with its own
// .cpp), and declares nothing itself. No header of the library includes this one; each
// includes the parts it uses.
//   mapping/slam/ekf.hpp                 the events of the filter and their Jacobians (Solà's names), Ekf
//   mapping/slam/simulator.hpp           the simulator (world, sensor, odometry, one run)
//   mapping/slam/consistency.hpp         NEES and chi-square bounds over Monte-Carlo runs
//   mapping/slam/observations.hpp        stereo landmarks as range-bearing observations
//   mapping/slam/trajectory.hpp          KITTI poses, dead reckoning, trajectory files, timestamps
//   mapping/slam/trajectory_metrics.hpp  APE (3-D, top view, SE(2)-aligned), RPE, NEES of a trajectory
//   mapping/slam/association.hpp         individual and joint compatibility (JCBB)
//   mapping/slam/landmark_slam.hpp       association settings, map management, LandmarkSlam
//   mapping/slam/synthetic.hpp           synthetic odometry and synthetic stereo frames
//   mapping/slam/filter_run.hpp          runs over a sequence (FilterRun, run_filter, run_sequence)
//   mapping/slam/odometry.hpp            stereo visual odometry and its runs
//   mapping/slam/report.hpp              the Monte-Carlo, sequence and timing reports
// Conventions: mapping/slam/ekf.hpp.
#pragma once

#include "mapping/slam/association.hpp"
#include "mapping/slam/consistency.hpp"
#include "mapping/slam/ekf.hpp"
#include "mapping/slam/filter_run.hpp"
#include "mapping/slam/landmark_slam.hpp"
#include "mapping/slam/observations.hpp"
#include "mapping/slam/odometry.hpp"
#include "mapping/slam/report.hpp"
#include "mapping/slam/simulator.hpp"
#include "mapping/slam/synthetic.hpp"
#include "mapping/slam/trajectory.hpp"
#include "mapping/slam/trajectory_metrics.hpp"
