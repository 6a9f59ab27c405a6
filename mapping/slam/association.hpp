// association.hpp: data association of a frame's observations with the mapped landmarks of
// an Ekf: individual compatibility (the gated candidates) and joint compatibility branch and
// bound (J. Neira, J. D. Tardós, "Data association in stochastic mapping using the joint
// compatibility test", IEEE Trans. Robotics and Automation 17(6), 2001).
#pragma once

#include "mapping/slam/ekf.hpp"
#include "mapping/slam/observations.hpp"

#include <vector>

namespace hc::slam {

/// An assignment: for each observation, the landmark id it is paired with, or -1.
struct Association {
    std::vector<int> landmark;
    int pairings = 0;
    double joint_mahalanobis2 = 0;   ///< of the chosen hypothesis (JCBB; 0 for nearest)
    long nodes = 0;                  ///< JCBB: nodes visited
    bool complete = true;            ///< JCBB: false when it stopped at the node limit
};

/// The observation noise of each candidate pairing, parallel to the candidates: noise[i][c] is
/// the covariance of observation i if it is landmark candidates[i][c]; empty: obs[i].R for all.
using PairingNoise = std::vector<std::vector<Mat2>>;

/// Individual gating + nearest neighbour: pairs (observation, candidate) taken greedily by
/// increasing Mahalanobis distance, one landmark per observation and one observation per
/// landmark. candidates[i] lists the landmark ids observation i may be paired with.
Association associate_nearest(const Ekf& ekf, const std::vector<RangeBearing>& obs,
                              const std::vector<std::vector<int>>& candidates, const PairingNoise& noise = {});

/// JCBB: among the hypotheses pairing observations with their candidates (each landmark at
/// most once), the one with the most pairings whose joint innovation passes the χ²(2k,
/// joint_probability) test, ties broken by the smaller joint Mahalanobis distance. Depth
/// first, candidates of each observation in increasing individual distance, a branch cut
/// when it cannot reach more pairings than the best found; at most `max_nodes` nodes.
Association associate_jcbb(const Ekf& ekf, const std::vector<RangeBearing>& obs,
                           const std::vector<std::vector<int>>& candidates, double joint_probability,
                           long max_nodes, const PairingNoise& noise = {});

}  // namespace hc::slam
