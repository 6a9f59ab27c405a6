// report.hpp: the reports of the library (slam.hpp): the Monte-Carlo report of the simulator
// (consistency.hpp), the sequence report of a run (filter_run.hpp), written as the run goes
// (SequenceFiles) or at once, a table of runs, and the update timing.
#pragma once

#include "mapping/slam/consistency.hpp"
#include "mapping/slam/ekf.hpp"
#include "mapping/slam/filter_run.hpp"
#include "mapping/slam/simulator.hpp"

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace hc::slam {

/// Writes the Monte-Carlo report into `dir`: report.md, nees.csv, states.csv (the first
/// run), summary.json, trajectory.png (trajectory and map with 3σ ellipses), nees.png,
/// rmse.png. `command` is quoted in report.md. PNGs need gnuplot; without it they are
/// skipped with a note in the report. Files are written atomically.
void write_simulation_report(const std::filesystem::path& dir, const SimConfig& config, const MonteCarlo& mc,
                             const std::string& command);

/// What a sequence report says besides the run's figures.
struct SequenceReportText {
    std::string title, command;
    /// Every flag's value, given or default, one `name=value` a line (the command's settings as
    /// the command line parser writes them); "" when the run did not come from the command line.
    std::string settings;
    /// Names the odometry-alone trajectory ("visual odometry alone", "synthetic odometry alone").
    std::string odometry_label;
    /// How the ground truth entered the run, or that there is none: the report's first sentence.
    std::string provenance;
};
/// A sequence report written as the run goes: states.csv and the trajectory files take one row
/// per frame (add, or sink() given to the run) into temporaries beside them in `dir` (created
/// when missing); commit() writes summary.json, report.md and the plots (gnuplot reading the
/// temporary states.csv) and renames every file into place. Destroyed without commit (the run
/// failed): the temporaries are removed, and `dir` when it was created and is empty; files
/// already in `dir` are left as they were. InputError when a file cannot be written.
class SequenceFiles {
public:
    explicit SequenceFiles(const std::filesystem::path& dir);
    ~SequenceFiles();
    SequenceFiles(const SequenceFiles&) = delete;
    SequenceFiles& operator=(const SequenceFiles&) = delete;
    void add(const FrameRecord& frame);
    /// add() as a run's sink (this object must outlive the run).
    FrameSink sink() {
        return [this](const FrameRecord& f) { add(f); };
    }
    void commit(const SequenceRun& run, const SequenceReportText& text);

private:
    void discard();
    enum { kStates, kEstimate, kPlanar, kOdometry, kTruth, kTum, kFiles };
    std::filesystem::path dir_;
    std::filesystem::path tmp_[kFiles];
    std::ofstream out_[kFiles];
    bool created_dir_ = false, committed_ = false, has_truth_ = false, extent_ = false;
    Vec2 lo_ = Vec2::Zero(), hi_ = Vec2::Zero();   // the positions' extent (the plot's frame)
};
/// Writes the sequence report: report.md (with a ground truth: 2-D and 3-D APE and the other
/// metrics of EKF-SLAM and of the odometry alone, wrong associations against truth; without,
/// the statement that nothing is scored), states.csv (per frame, with the pose NEES),
/// summary.json, estimate_kitti.txt and estimate_tum.txt (6-DoF, SequenceRun::estimate_3d,
/// timestamps run.timestamps), estimate_planar_kitti.txt (the filter's top view),
/// dead_reckoning_kitti.txt (the odometry alone, 6-DoF), truth_kitti.txt (with a ground truth),
/// trajectory.png, map_size.png: SequenceFiles fed with the run's kept frames. std::invalid_argument
/// unless the run kept its frames (RunRecord::keep) and has one timestamp per frame.
void write_sequence_report(const std::filesystem::path& dir, const SequenceRun& run, const SequenceReportText& text);
/// A Markdown table with one row per (sequence name, run).
std::string sequences_markdown(const std::vector<std::pair<std::string, SequenceRun>>& runs,
                               const std::string& odometry_label);

/// One point of the update timing: landmarks, milliseconds per step, per form.
struct TimingRow {
    int landmarks = 0;
    double structured_ms = 0, dense_kzk_ms = 0, dense_ms = 0;   ///< 0 = not measured
    /// dense_ms is k times one measured (I − KH)P update, not a measured step.
    bool dense_from_single_update = false;
};
/// Writes timing.csv and timing.png (log-log, with the thesis's Table 3 figures).
void write_timing_report(const std::filesystem::path& dir, const std::vector<TimingRow>& rows);

}  // namespace hc::slam
