// report.cpp: the Markdown/CSV/JSON/PNG reports of the simulation, the sequence runs and
// the update timing. Plots are drawn by gnuplot from inline data blocks; every file is
// written to a temporary beside its target, then renamed (util::write_file_atomic).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "mapping/slam/report.hpp"
#include "mapping/slam/trajectory.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;

namespace hc::slam {

namespace {

fs::path temp_beside(const fs::path& target) {
    std::string name = ".";   // appended rather than "." + ...: GCC 12's -Wrestrict misfires on the latter here
    name += target.filename().string();
    name += ".tmp.";
    name += std::to_string(::getpid());
    return target.parent_path() / name;
}

void make_dir(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError("cannot create the output directory '" + dir.string() + "': " + ec.message());
}

bool have_gnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

// Runs gnuplot on `script` (which draws to the file named by the variable `out`), writing
// `png` atomically. Returns false (with a warning) when gnuplot is absent or fails.
bool plot(const fs::path& png, const std::string& script, int width = 1000, int height = 700) {
    if (!have_gnuplot()) {
        std::fprintf(stderr, "slam report: warning: gnuplot not found, %s not drawn\n", png.filename().c_str());
        return false;
    }
    const fs::path tmp_png = temp_beside(png), gp = temp_beside(png.string() + ".gp");
    util::write_file_atomic(gp, "set terminal pngcairo size " + std::to_string(width) + "," + std::to_string(height) +
                 " font ',11'\nset output '" + tmp_png.string() + "'\n" + script);
    const int rc = std::system(("gnuplot '" + gp.string() + "' 2>/dev/null").c_str());
    fs::remove(gp);
    if (rc != 0 || !fs::exists(tmp_png)) {
        std::fprintf(stderr, "slam report: warning: gnuplot failed, %s not drawn\n", png.filename().c_str());
        fs::remove(tmp_png);
        return false;
    }
    fs::rename(tmp_png, png);
    return true;
}

std::string num(double v) {
    if (!std::isfinite(v)) return "NaN";
    std::ostringstream o;
    o << std::setprecision(8) << v;
    return o.str();
}

// Points of the k-sigma ellipse of a 2-D Gaussian, closed, one "x y" per line, then a blank line.
std::string ellipse(const Vec2& c, const Mat2& P, double k) {
    // principal axes of [a b; b d]: λ = (a+d)/2 ± √(((a−d)/2)² + b²), major axis at φ
    const double m = (P(0, 0) + P(1, 1)) / 2, h = std::hypot((P(0, 0) - P(1, 1)) / 2, P(0, 1));
    const double s1 = k * std::sqrt(std::max(m + h, 0.0)), s2 = k * std::sqrt(std::max(m - h, 0.0));
    const double phi = 0.5 * std::atan2(2 * P(0, 1), P(0, 0) - P(1, 1));
    Mat2 rot;
    rot << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
    std::ostringstream o;
    for (int i = 0; i <= 36; ++i) {
        const double a = 2 * std::numbers::pi * i / 36;
        const Vec2 p = c + rot * Vec2(s1 * std::cos(a), s2 * std::sin(a));
        o << num(p.x()) << ' ' << num(p.y()) << '\n';
    }
    return o.str() + "\n";
}

std::string block(const std::string& name, const std::string& data) { return "$" + name + " << EOD\n" + data + "EOD\n"; }

std::string poses_xy(const std::vector<Pose>& v) {
    std::string s;
    for (const auto& p : v) s += num(p.x()) + ' ' + num(p.y()) + '\n';
    return s;
}

// A top view framed on what it shows: the axes span `xy` (trajectories, landmark means) with
// a margin at equal scale, the canvas takes the data's shape (so the map fills it, ellipses
// reaching beyond are clipped), the key sits beside the map and the title, two lines, is
// centred on the canvas rather than on the plot, so a narrow map does not clip it.
struct TopView {
    std::string script;   ///< the set commands before `plot`
    int width = 1000, height = 700;
};
TopView top_view(const std::vector<Vec2>& xy, const std::string& title, const std::string& subtitle,
                 const std::string& xlabel, const std::string& ylabel) {
    std::vector<double> xs, ys;
    for (const auto& p : xy) xs.push_back(p.x()), ys.push_back(p.y());
    util::AxisRange x = util::axis_range(xs, 0.05, -1e300, 1e300, 2.0), y = util::axis_range(ys, 0.05, -1e300, 1e300, 2.0);
    // the plot area (about 800 px on its long side) in the data's aspect, within 1:3 either way
    const double aspect = std::clamp((y.hi - y.lo) / (x.hi - x.lo), 1.0 / 3, 3.0);
    const int long_side = 800;
    const int pw = aspect >= 1 ? static_cast<int>(long_side / aspect) : long_side;
    const int ph = aspect >= 1 ? long_side : static_cast<int>(long_side * aspect);
    TopView v;
    v.width = std::max(640, pw + 330);    // axis labels and the key beside the map; the title fits
    v.height = ph + 150;                  // the two-line title and the x label
    std::ostringstream o;
    o << "set size ratio -1\nset grid\nset key outside right top\nset xlabel '" << xlabel << "'\nset ylabel '" << ylabel
      << "'\nset xrange " << x.gnuplot() << "\nset yrange " << y.gnuplot() << "\nset tmargin 4\n"
      << "set label 1 \"" << title << "\\n" << subtitle << "\" at screen 0.5, screen 0.975 center front\n";
    v.script = o.str();
    return v;
}

std::vector<Vec2> positions(std::initializer_list<const std::vector<Pose>*> trajectories, const std::vector<Vec2>& points) {
    std::vector<Vec2> v(points);
    for (const auto* t : trajectories)
        for (const auto& p : *t) v.push_back(p.head<2>());
    return v;
}

const char* layout_name(Layout l) { return l == Layout::Cloister ? "cloister" : "random"; }

}  // namespace

namespace {

void save_nees_csv(const fs::path& dir, const MonteCarlo& mc) {
    const int T = static_cast<int>(mc.pose_nees.size());
    std::ostringstream csv;
    csv << "step,pose_nees,pose_lo,pose_hi,map_nees_per_dof,map_lo,map_hi,position_rmse_m,heading_rmse_rad,map_rmse_m\n";
    for (int k = 0; k < T; ++k)
        csv << k << ',' << num(mc.pose_nees[k]) << ',' << num(mc.pose_lo) << ',' << num(mc.pose_hi) << ','
            << num(mc.map_nees_per_dof[k]) << ',' << num(mc.map_lo[k]) << ',' << num(mc.map_hi[k]) << ','
            << num(mc.position_rmse[k]) << ',' << num(mc.heading_rmse[k]) << ',' << num(mc.map_rmse[k]) << '\n';
    util::write_file_atomic(dir / "nees.csv", csv.str());
}

void save_simulation_states(const fs::path& dir, const RunTrace& t) {
    std::ostringstream st;
    st << "step,true_x,true_y,true_theta,est_x,est_y,est_theta,sigma_x,sigma_y,sigma_theta,pose_nees,landmarks\n";
    for (size_t k = 0; k < t.truth.size(); ++k) {
        st << k;
        for (int i = 0; i < 3; ++i) st << ',' << num(t.truth[k](i));
        for (int i = 0; i < 3; ++i) st << ',' << num(t.estimate[k](i));
        for (int i = 0; i < 3; ++i) st << ',' << num(std::sqrt(t.pose_cov[k](i, i)));
        st << ',' << num(t.pose_nees[k]) << ',' << t.map_dof[k] / 2 << '\n';
    }
    util::write_file_atomic(dir / "states.csv", st.str());
}

void save_simulation_summary(const fs::path& dir, const SimConfig& c, const MonteCarlo& mc, const std::string& command) {
    nlohmann::json j;
    j["command"] = command;
    j["config"] = {{"layout", layout_name(c.layout)}, {"landmarks", c.landmarks}, {"half_size_m", c.half_size},
                   {"radius_m", c.radius}, {"step_m", c.step}, {"steps", c.steps},
                   {"sigma_range_m", c.sensor.sigma_range}, {"sigma_bearing_rad", c.sensor.sigma_bearing},
                   {"max_range_m", c.sensor.max_range}, {"fov_rad", c.sensor.fov},
                   {"sigma_dx_m", c.odometry.sigma_dx}, {"sigma_dtheta_rad", c.odometry.sigma_dtheta}};
    j["runs"] = mc.runs;
    j["first_seed"] = mc.first_seed;
    j["confidence"] = mc.confidence;
    j["pose_nees"] = {{"average", mc.pose_nees_average}, {"lo", mc.pose_lo}, {"hi", mc.pose_hi},
                      {"fraction_inside", mc.pose_inside}};
    j["map_nees_per_dof"] = {{"average", mc.map_nees_per_dof_average}, {"lo_final", mc.map_lo.back()},
                             {"hi_final", mc.map_hi.back()}, {"fraction_inside", mc.map_inside}};
    j["final_rmse"] = {{"position_m", mc.position_rmse.back()}, {"heading_rad", mc.heading_rmse.back()},
                       {"map_m", mc.map_rmse.back()}};
    util::write_file_atomic(dir / "summary.json", j.dump(2) + "\n");
}

// The first run's trajectory and map: true landmarks, the map's and the robot's 3-sigma ellipses.
bool plot_simulation_trajectory(const fs::path& dir, const RunTrace& t) {
    std::string lm, est_lm;
    for (const auto& p : t.world.landmarks) lm += num(p.x()) + ' ' + num(p.y()) + '\n';
    for (size_t i = 0; i < t.final_map.size(); ++i) est_lm += ellipse(t.final_map[i], t.final_map_cov[i], 3);
    std::string robot_ell;
    for (size_t k = 0; k < t.estimate.size(); k += std::max<size_t>(1, t.estimate.size() / 12))
        robot_ell += ellipse(t.estimate[k].head<2>(), t.pose_cov[k].topLeftCorner<2, 2>(), 3);
    const TopView sim_view = top_view(positions({&t.truth, &t.estimate}, t.world.landmarks), "Run of seed 1",
                                      "trajectory and map, 3-sigma ellipses", "x (m)", "y (m)");
    return plot(dir / "trajectory.png",
        block("lm", lm) + block("truth", poses_xy(t.truth)) + block("est", poses_xy(t.estimate)) +
        block("ell", est_lm) + block("rell", robot_ell) + sim_view.script +
        "plot $lm w p pt 7 ps 0.8 lc rgb 'black' t 'true landmarks', $ell w l lc rgb 'red' t 'landmark 3{/Symbol s}',"
        " $truth w l lw 2 lc rgb 'black' t 'true trajectory', $est w l lw 2 lc rgb 'blue' t 'estimate',"
        " $rell w l lc rgb 'blue' dt 2 t 'robot 3{/Symbol s}'\n", sim_view.width, sim_view.height);
}

// The pose NEES and the map NEES per dof over steps, each panel framed on its curve and its
// bounds (and the expected value).
bool plot_nees(const fs::path& dir, const MonteCarlo& mc) {
    const int T = static_cast<int>(mc.pose_nees.size());
    std::string pn, mn;
    for (int k = 0; k < T; ++k) {
        pn += std::to_string(k) + ' ' + num(mc.pose_nees[k]) + '\n';
        mn += std::to_string(k) + ' ' + num(mc.map_nees_per_dof[k]) + ' ' + num(mc.map_lo[k]) + ' ' + num(mc.map_hi[k]) + '\n';
    }
    std::vector<double> pose_y(mc.pose_nees.begin(), mc.pose_nees.end()), map_y(mc.map_nees_per_dof.begin(),
                                                                                  mc.map_nees_per_dof.end());
    pose_y.insert(pose_y.end(), {mc.pose_lo, mc.pose_hi, 3.0});
    map_y.insert(map_y.end(), mc.map_lo.begin(), mc.map_lo.end());
    map_y.insert(map_y.end(), mc.map_hi.begin(), mc.map_hi.end());
    map_y.push_back(1.0);
    std::ostringstream ns;
    ns << block("pn", pn) << block("mn", mn) << "set multiplot layout 2,1\nset grid\nset key top right\n"
       << "set title 'Robot pose NEES, mean of " << mc.runs << " runs, " << 100 * mc.confidence << " % bounds'\n"
       << "set xlabel 'step'\nset ylabel 'NEES (3 dof)'\nset yrange " << util::axis_range(pose_y, 0.08, 0.0).gnuplot() << "\n"
       << "plot $pn u 1:2 w l lw 2 t 'mean NEES', " << mc.pose_lo << " w l dt 2 lc rgb 'red' t 'bounds', " << mc.pose_hi
       << " w l dt 2 lc rgb 'red' notitle, 3 w l lc rgb 'gray' t 'dof'\n"
       << "set title 'Map NEES per degree of freedom (all mapped landmarks jointly)'\nset ylabel 'NEES / dof'\n"
       << "set yrange " << util::axis_range(map_y, 0.08, 0.0).gnuplot() << "\nplot $mn u 1:2 w l lw 2 t 'mean NEES / dof', $mn u 1:3 w l dt 2 lc rgb 'red' t 'bounds',"
       << " $mn u 1:4 w l dt 2 lc rgb 'red' notitle, 1 w l lc rgb 'gray' notitle\nunset multiplot\n";
    return plot(dir / "nees.png", ns.str());
}

bool plot_rmse(const fs::path& dir, const MonteCarlo& mc) {
    const int T = static_cast<int>(mc.pose_nees.size());
    std::string rm;
    for (int k = 0; k < T; ++k)
        rm += std::to_string(k) + ' ' + num(mc.position_rmse[k]) + ' ' + num(mc.heading_rmse[k] * 180 / std::numbers::pi) +
              ' ' + num(mc.map_rmse[k]) + '\n';
    return plot(dir / "rmse.png", block("rm", rm) +
        "set grid\nset xlabel 'step'\nset ylabel 'RMSE (m)'\nset y2label 'heading RMSE (deg)'\nset y2tics\nset ytics nomirror\n"
        "set title 'RMSE over " + std::to_string(mc.runs) + " runs'\n"
        "plot $rm u 1:2 w l lw 2 t 'position', $rm u 1:4 w l lw 2 t 'landmarks', $rm u 1:3 axes x1y2 w l lw 2 t 'heading'\n");
}

/// The simulation's report.md, linking the plots that were drawn.
std::string simulation_markdown(const SimConfig& c, const MonteCarlo& mc, const std::string& command, bool traj_png,
                                bool nees_png, bool rmse_png) {
    std::ostringstream md;
    md << std::setprecision(4);
    md << "# EKF-SLAM simulation: Monte-Carlo consistency\n\nCommand: `" << command << "`\n\n"
       << "| parameter | value |\n|---|---|\n"
       << "| world | " << layout_name(c.layout) << ", " << c.landmarks << " landmarks, half size " << c.half_size << " m |\n"
       << "| trajectory | circle of radius " << c.radius << " m, " << c.steps << " steps of " << c.step << " m |\n"
       << "| sensor | σ range " << c.sensor.sigma_range << " m, σ bearing " << c.sensor.sigma_bearing * 180 / std::numbers::pi
       << "°, range ≤ " << c.sensor.max_range << " m, field of view " << c.sensor.fov * 180 / std::numbers::pi << "° |\n"
       << "| odometry | σ dx " << c.odometry.sigma_dx << " m, σ dθ " << c.odometry.sigma_dtheta * 180 / std::numbers::pi << "° per step |\n"
       << "| runs | " << mc.runs << " seeds from " << mc.first_seed << " |\n\n"
       << "## Consistency (" << 100 * mc.confidence << " % two-sided chi-square bounds of the mean over runs)\n\n"
       << "| quantity | average over steps | bounds | steps inside |\n|---|---|---|---|\n"
       << "| robot pose NEES (3 dof) | " << mc.pose_nees_average << " | [" << mc.pose_lo << ", " << mc.pose_hi << "] | "
       << 100 * mc.pose_inside << " % |\n"
       << "| map NEES per dof | " << mc.map_nees_per_dof_average << " | [" << mc.map_lo.back() << ", " << mc.map_hi.back()
       << "] (last step) | " << 100 * mc.map_inside << " % |\n\n"
       << "Final RMSE: position " << mc.position_rmse.back() << " m, heading "
       << mc.heading_rmse.back() * 180 / std::numbers::pi << "°, landmarks " << mc.map_rmse.back() << " m.\n\n"
       << "The pose NEES is undefined until the pose covariance has full rank (the first motion leaves it of rank 2).\n\n";
    if (traj_png) md << "![trajectory and map](trajectory.png)\n\n";
    if (nees_png) md << "![NEES](nees.png)\n\n";
    if (rmse_png) md << "![RMSE](rmse.png)\n\n";
    if (!(traj_png && nees_png && rmse_png)) md << "Some plots were not drawn (gnuplot missing or failed).\n\n";
    md << "Files: `nees.csv` (per step over runs), `states.csv` (the run of the first seed), `summary.json`.\n";
    return md.str();
}

}  // namespace

void write_simulation_report(const fs::path& dir, const SimConfig& c, const MonteCarlo& mc, const std::string& command) {
    make_dir(dir);
    save_nees_csv(dir, mc);
    save_simulation_states(dir, mc.first);
    save_simulation_summary(dir, c, mc, command);
    const bool traj_png = plot_simulation_trajectory(dir, mc.first);
    const bool nees_png = plot_nees(dir, mc);
    const bool rmse_png = plot_rmse(dir, mc);
    util::write_file_atomic(dir / "report.md", simulation_markdown(c, mc, command, traj_png, nees_png, rmse_png));
}

namespace {
nlohmann::json metrics_json(const TrajectoryMetrics& m) {
    return {{"ape_m", m.ape},          {"ape_se2_m", m.ape_se2},   {"ape_percent_of_path", m.ape_percent()},
            {"rpe_m", m.rpe},          {"rpe_heading_rad", m.rpe_heading}, {"final_error_m", m.final_error},
            {"nees_mean", m.nees_frames ? nlohmann::json(m.nees_mean) : nlohmann::json(nullptr)},
            {"nees_frames", m.nees_frames}, {"nees_bounds_95", {m.nees_lo, m.nees_hi}},
            {"nees_frames_within_chi2_95", m.nees_within_95}};
}

const char* const kStatesHeader =
    "frame,true_x,true_y,true_theta,est_x,est_y,est_theta,sigma_x,sigma_y,sigma_theta,odo_x,odo_y,odo_theta,"
    "nees_slam,nees_odometry,observed,matched,added,rejected_by_descriptor,removed,map_size,matched_agreeing,"
    "matched_checked,matched_wrong\n";

// One frame's row of states.csv; past the ground truth (or without one) the truth and NEES are NaN.
std::string states_row(const FrameRecord& r) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::ostringstream st;
    st << r.frame;
    for (int i = 0; i < 3; ++i) st << ',' << num(r.truth ? (*r.truth)(i) : nan);
    for (int i = 0; i < 3; ++i) st << ',' << num(r.estimate(i));
    for (int i = 0; i < 3; ++i) st << ',' << num(std::sqrt(r.pose_cov(i, i)));
    for (int i = 0; i < 3; ++i) st << ',' << num(r.dead_reckoning(i));
    st << ',' << num(r.nees_slam) << ',' << num(r.nees_odometry);
    const FrameStats& f = r.stats;
    st << ',' << f.observed << ',' << f.matched << ',' << f.added << ',' << f.rejected_by_descriptor << ','
       << f.removed << ',' << f.map_size << ',' << f.matched_agreeing << ',' << f.matched_checked << ','
       << f.matched_wrong << '\n';
    return st.str();
}

/// A command's settings (`name=value` lines) as a JSON object of their texts.
nlohmann::json settings_json(const std::string& settings) {
    nlohmann::json j = nlohmann::json::object();
    std::istringstream in(settings);
    for (std::string line; std::getline(in, line);) {
        const std::size_t eq = line.find('=');
        if (eq != std::string::npos) j[line.substr(0, eq)] = line.substr(eq + 1);
    }
    return j;
}

void save_sequence_summary(const fs::path& file, const SequenceRun& r, const SequenceReportText& text) {
    const RunTotals& t = r.totals;
    const bool scored = r.scored_frames > 0;
    const std::string& odometry_label = text.odometry_label;
    nlohmann::json j;
    j["command"] = text.command;
    if (!text.settings.empty()) j["settings"] = settings_json(text.settings);
    j["frames"] = r.frame_count;
    j["scored_frames"] = r.scored_frames;
    j["ground_truth"] = scored;
    j["odometry"] = odometry_label;
    j["timestamps"] = r.timestamps_from;
    if (scored) j["truth_pairing"] = r.truth_pairing;
    j["height_roll_pitch"] = r.spatial_from_odometry ? "visual odometry's 6-DoF steps" : "none (level, height 0)";
    if (scored) {
        j["ate_m"] = {{"slam", r.ate_slam}, {"dead_reckoning", r.ate_dead_reckoning}};
        j["ape_3d_m"] = {{"slam", r.ape_3d_slam}, {"dead_reckoning", r.ape_3d_dead_reckoning}};
        j["slam"] = metrics_json(r.slam_metrics);
        j["odometry_alone"] = metrics_json(r.odometry_metrics);
        j["path_length_m"] = r.slam_metrics.path_length;
    }
    j["observations"] = t.observed;
    j["matched"] = t.matched;
    j["matched_not_corrected"] = t.not_corrected;
    j["map_size"] = {{"final", t.final_map_size}, {"peak", t.peak}};
    j["matches_with_id_hints"] = {{"total", t.hinted}, {"agreeing", t.agreeing}};
    j["matches_checked_against_truth"] = {{"total", t.checked}, {"wrong", t.wrong}};
    j["jcbb_frames_cut_at_node_limit"] = t.jcbb_cut;
    if (r.disparity_estimated)
        j["disparity_correction_px"] = {{"final", r.disparity_final}, {"min", r.disparity_min}, {"max", r.disparity_max}};
    j["pixel_noise_variance_factor"] = r.noise_scale;
    util::write_file_atomic(file, j.dump(2) + "\n");
}

// A file name in gnuplot's single quotes (appended: GCC 12's -Wrestrict misfires on "'" + ...).
std::string gnuplot_file(const fs::path& file) {
    std::string q = "'";
    q += file.string();
    q += '\'';
    return q;
}

// The top view's trajectories from states.csv (columns: truth 2:3, estimate 5:6, odometry alone
// 11:12), framed on `extent` and the map, with the map's 3σ ellipses.
bool plot_sequence_trajectory(const fs::path& dir, const fs::path& states, const SequenceRun& r,
                              const std::vector<Vec2>& extent, const std::string& title,
                              const std::string& odometry_label) {
    std::string ell;
    for (size_t i = 0; i < r.map.size(); ++i) ell += ellipse(r.map[i], r.map_cov[i], 3);
    std::replace(ell.begin(), ell.end(), ' ', ',');
    std::vector<Vec2> xy(r.map);
    xy.insert(xy.end(), extent.begin(), extent.end());
    const TopView view = top_view(xy, title, "top view, final map with 3-sigma ellipses", "forward x (m)", "left y (m)");
    const std::string file = gnuplot_file(states);
    const std::string truth_curve =
        r.scored_frames == 0 ? "" : " " + file + " every ::1 u 2:3 w l lw 2 lc rgb 'black' t 'ground truth',";
    return plot(dir / "trajectory.png",
        block("ell", ell) + "set datafile separator ','\n" + view.script +
        "plot $ell w l lc rgb '#cc8888' t 'landmark 3{/Symbol s}'," + truth_curve + " " + file +
        " every ::1 u 5:6 w l lw 2 lc rgb 'blue' t 'EKF-SLAM', " + file + " every ::1 u 11:12 w l lw 2 dt 2 lc rgb "
        "'orange' t '" + odometry_label + "'\n", view.width, view.height);
}

// Map size, matched and added per frame from states.csv (columns 21, 17, 18).
bool plot_map_size(const fs::path& dir, const fs::path& states, const std::string& title) {
    const std::string file = gnuplot_file(states);
    return plot(dir / "map_size.png",
        "set datafile separator ','\nset grid\nset xlabel 'frame'\nset ylabel 'landmarks'\nset title '" + title +
        ": map size and associations'\nplot " + file + " every ::1 u 1:21 w l lw 2 t 'map size', " + file +
        " every ::1 u 1:17 w l t 'matched', " + file + " every ::1 u 1:18 w l t 'added'\n");
}

// A mean pose NEES with the 95 % bounds of a mean over its frames and the share of frames under
// χ²(0.95; 3): "mean [lo, hi], p % ≤ 7.81"; "-" when no NEES is defined.
std::string nees_cell(const TrajectoryMetrics& m) {
    if (!m.nees_frames) return "-";
    std::ostringstream o;
    o << std::setprecision(4) << m.nees_mean << " [" << std::setprecision(3) << m.nees_lo << ", " << m.nees_hi << "], "
      << std::setprecision(3) << 100 * m.nees_within_95 << " % ≤ 7.81";
    return o.str();
}

// Where the 6-DoF files' height, roll and pitch come from.
std::string height_source(const SequenceRun& r) {
    return r.spatial_from_odometry ? "heading and top-view position of the filter, height, roll and pitch of visual "
                                     "odometry's 6-DoF steps"
                                   : "the top view, level at height 0";
}

// One row of the report's metrics table.
std::string metrics_row(const std::string& name, const TrajectoryMetrics& m, double ape_3d) {
    std::ostringstream o;
    o << std::setprecision(4) << "| " << name << " | " << m.ape << " | " << ape_3d << " | " << m.ape_percent() << " | " << m.ape_se2
      << " | " << m.rpe << " | " << m.rpe_heading * 180 / std::numbers::pi << " | " << m.final_error << " | "
      << nees_cell(m) << " |\n";
    return o.str();
}

/// The report's scores: the metrics table and the frames' counts, or the statement that there
/// is no ground truth.
std::string scores_markdown(const SequenceRun& r, const std::string& odometry_label) {
    const RunTotals& t = r.totals;
    std::ostringstream md;
    md << std::setprecision(4);
    if (r.scored_frames == 0) {
        md << "No ground truth: the trajectory and the map are not scored.\n\n"
           << r.frame_count << " frames; " << t.observed << " observations, " << t.matched
           << " associated; map size final " << t.final_map_size << ", peak " << t.peak << ".\n\n";
        return md.str();
    }
    if (r.scored_frames < r.frame_count)
        md << "The ground truth covers the first " << r.scored_frames << " of the " << r.frame_count
           << " frames (--score-overlap): every score below is of those frames.\n\n";
    md << "APE 2-D is on the top view; APE 3-D on the 6-DoF poses of `estimate_kitti.txt` and "
          "`dead_reckoning_kitti.txt` against `truth_kitti.txt` (" << height_source(r)
       << "), as evo_ape computes it on those files without alignment.\n\n"
       << "| trajectory | APE 2-D (m) | APE 3-D (m) | APE 2-D % of path | APE SE(2)-aligned (m) | RPE per frame (m) | "
          "RPE heading (°) | final error (m) | mean pose NEES [95 % bounds of the mean], frames ≤ χ²(0.95; 3) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n"
       << metrics_row("EKF-SLAM", r.slam_metrics, r.ape_3d_slam)
       << metrics_row(odometry_label, r.odometry_metrics, r.ape_3d_dead_reckoning) << "\n"
       << r.frame_count << " frames, path length " << r.slam_metrics.path_length << " m; " << t.observed
       << " observations, " << t.matched << " associated; map size final " << t.final_map_size << ", peak "
       << t.peak << ".\n\n";
    return md.str();
}

/// A sequence's report.md, linking the plots that were drawn.
std::string sequence_markdown(const SequenceRun& r, const SequenceReportText& text, bool traj_png, bool map_png,
                              bool truth_file) {
    const RunTotals& t = r.totals;
    std::ostringstream md;
    md << std::setprecision(4);
    md << "# EKF-SLAM on " << text.title << "\n\nCommand: `" << text.command << "`\n\n" << text.provenance << "\n\n"
       << scores_markdown(r, text.odometry_label);
    if (t.checked > 0)
        md << "Associations checked against the ground truth (observation and the landmark's first observation "
              "placed in the world with the true poses, χ²(2) 0.999): " << t.wrong << " of " << t.checked
           << " wrong (" << 100.0 * t.wrong / t.checked << " %).\n\n";
    if (t.hinted > 0)
        md << "Matches whose observation and landmark carry id hints: " << t.hinted << ", of which " << t.agreeing
           << " agree (" << 100.0 * t.agreeing / t.hinted << " %).\n\n";
    if (r.disparity_estimated)
        md << "Disparity correction estimated by the visual odometry from the frames alone (no ground truth): "
           << r.disparity_final << " px at the end of the run (from " << r.disparity_min << " to " << r.disparity_max
           << " px over the frames); the filter saw every disparity that much larger.\n\n";
    if (t.jcbb_cut > 0) md << "JCBB stopped at its node limit in " << t.jcbb_cut << " frames (best hypothesis so far kept).\n\n";
    if (traj_png) md << "![trajectory](trajectory.png)\n\n";
    if (map_png) md << "![map size](map_size.png)\n\n";
    md << "Files (KITTI camera frame: x right, y down, z forward): `states.csv` (per frame, with the pose NEES), "
          "`summary.json`, `estimate_kitti.txt` and `estimate_tum.txt` (the estimate, 6-DoF: " << height_source(r)
       << "; TUM timestamps from " << r.timestamps_from << "), `estimate_planar_kitti.txt` (the filter's top view, "
          "height 0), `dead_reckoning_kitti.txt` (" << text.odometry_label << ", 6-DoF as the estimate)"
       << (!truth_file ? "" : ", `truth_kitti.txt` (the ground truth's poses of the frames scored, paired with "
                                      "the frames " + r.truth_pairing + ")") << ".\n";
    if (!text.settings.empty())
        md << "\nSettings, every flag given or at its default (also `settings` in `summary.json`):\n\n```\n"
           << text.settings << (text.settings.ends_with('\n') ? "" : "\n") << "```\n";
    return md.str();
}

const char* const kSequenceFiles[] = {"states.csv", "estimate_kitti.txt", "estimate_planar_kitti.txt",
                                      "dead_reckoning_kitti.txt", "truth_kitti.txt", "estimate_tum.txt"};
}  // namespace

SequenceFiles::SequenceFiles(const fs::path& dir) : dir_(dir) {
    created_dir_ = !fs::exists(dir);
    make_dir(dir);
    for (int i = 0; i < kFiles; ++i) {
        tmp_[i] = temp_beside(dir / kSequenceFiles[i]);
        out_[i].open(tmp_[i], std::ios::binary);
        if (!out_[i]) {
            discard();
            throw InputError("cannot write '" + (dir / kSequenceFiles[i]).string() + "'");
        }
    }
    out_[kStates] << kStatesHeader;
}

SequenceFiles::~SequenceFiles() {
    if (!committed_) discard();
}

void SequenceFiles::discard() {
    std::error_code ec;
    for (int i = 0; i < kFiles; ++i) {
        if (out_[i].is_open()) out_[i].close();
        if (!tmp_[i].empty()) fs::remove(tmp_[i], ec);
    }
    if (created_dir_ && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
}

void SequenceFiles::add(const FrameRecord& f) {
    out_[kStates] << states_row(f);
    out_[kEstimate] << kitti_line(f.estimate_3d);
    out_[kPlanar] << kitti_line(kitti_pose(f.estimate));
    out_[kOdometry] << kitti_line(f.dead_reckoning_3d);
    if (f.truth_3d) {
        out_[kTruth] << kitti_line(*f.truth_3d);
        has_truth_ = true;
    }
    out_[kTum] << tum_line(f.estimate_3d, f.timestamp);
    const auto extend = [this](const Vec2& p) {
        if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return;
        lo_ = extent_ ? lo_.cwiseMin(p) : p;
        hi_ = extent_ ? hi_.cwiseMax(p) : p;
        extent_ = true;
    };
    if (f.truth) extend(f.truth->head<2>());
    extend(f.estimate.head<2>());
    extend(f.dead_reckoning.head<2>());
}

void SequenceFiles::commit(const SequenceRun& run, const SequenceReportText& text) {
    for (int i = 0; i < kFiles; ++i) {
        out_[i].close();
        if (!out_[i]) throw InputError("cannot write '" + (dir_ / kSequenceFiles[i]).string() + "'");
    }
    const std::vector<Vec2> extent = extent_ ? std::vector<Vec2>{lo_, hi_} : std::vector<Vec2>{};
    const bool traj_png = plot_sequence_trajectory(dir_, tmp_[kStates], run, extent, text.title, text.odometry_label);
    const bool map_png = plot_map_size(dir_, tmp_[kStates], text.title);
    save_sequence_summary(dir_ / "summary.json", run, text);
    util::write_file_atomic(dir_ / "report.md", sequence_markdown(run, text, traj_png, map_png, has_truth_));
    for (int i = 0; i < kFiles; ++i) {
        if (i == kTruth && !has_truth_) continue;
        std::error_code ec;
        fs::rename(tmp_[i], dir_ / kSequenceFiles[i], ec);
        if (ec) throw InputError("cannot write '" + (dir_ / kSequenceFiles[i]).string() + "': " + ec.message());
    }
    std::error_code ec;
    if (!has_truth_) fs::remove(tmp_[kTruth], ec);
    committed_ = true;
}

void write_sequence_report(const fs::path& dir, const SequenceRun& r, const SequenceReportText& text) {
    const size_t n = r.estimate.size();
    if (r.timestamps.size() != n || n != r.frame_count)
        throw std::invalid_argument("write_sequence_report: a run that kept its frames, one timestamp per frame");
    SequenceFiles files(dir);
    for (size_t k = 0; k < n; ++k) {
        FrameRecord f;
        f.frame = k;
        const bool scored = k < r.truth.size();
        f.truth = scored ? &r.truth[k] : nullptr;
        f.truth_3d = k < r.truth_3d.size() ? &r.truth_3d[k] : nullptr;
        f.estimate = r.estimate[k];
        f.dead_reckoning = r.dead_reckoning[k];
        f.pose_cov = r.pose_cov[k];
        f.estimate_3d = r.estimate_3d[k];
        f.dead_reckoning_3d = r.dead_reckoning_3d[k];
        f.nees_slam = scored ? r.slam_metrics.nees[k] : std::numeric_limits<double>::quiet_NaN();
        f.nees_odometry = scored ? r.odometry_metrics.nees[k] : std::numeric_limits<double>::quiet_NaN();
        f.timestamp = r.timestamps[k];
        f.stats = r.frames[k];
        files.add(f);
    }
    files.commit(r, text);
}

std::string sequences_markdown(const std::vector<std::pair<std::string, SequenceRun>>& runs,
                               const std::string& odometry_label) {
    std::ostringstream md;
    md << std::setprecision(4)
       << "| sequence | frames | path (m) | APE EKF-SLAM (m) | APE 3-D (m) | % of path | APE SE(2) (m) | RPE (m) | mean NEES [95 % bounds], frames ≤ 7.81 | APE "
       << odometry_label << " (m) | % of path | RPE (m) | mean NEES [95 % bounds], frames ≤ 7.81 | matched | wrong vs truth |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& [name, r] : runs) {
        const RunTotals& t = r.totals;
        const auto& s = r.slam_metrics;
        const auto& o = r.odometry_metrics;
        if (r.scored_frames == 0) {
            md << "| " << name << " | " << r.frame_count << " | no ground truth |||||||||||| " << t.matched
               << " | - |\n";
            continue;
        }
        md << "| " << name << " | " << r.frame_count << " | " << s.path_length << " | " << s.ape << " | "
           << r.ape_3d_slam << " | " << s.ape_percent() << " | " << s.ape_se2 << " | " << s.rpe << " | "
           << nees_cell(s) << " | " << o.ape << " | " << o.ape_percent()
           << " | " << o.rpe << " | " << nees_cell(o) << " | " << t.matched
           << " | " << t.wrong << " of " << t.checked << " |\n";
    }
    return md.str();
}

void write_timing_report(const fs::path& dir, const std::vector<TimingRow>& rows) {
    make_dir(dir);
    std::ostringstream csv, data;
    csv << "landmarks,state_dim,structured_ms,dense_kzk_ms,dense_ms,dense_from_single_update\n";
    for (const auto& r : rows) {
        csv << r.landmarks << ',' << 3 + 2 * r.landmarks << ',' << num(r.structured_ms) << ',' << num(r.dense_kzk_ms)
            << ',' << num(r.dense_ms) << ',' << (r.dense_from_single_update ? 1 : 0) << '\n';
        const auto v = [](double x) { return x > 0 ? num(x) : std::string("NaN"); };
        data << r.landmarks << ' ' << v(r.structured_ms) << ' ' << v(r.dense_kzk_ms) << ' '
             << (r.dense_from_single_update ? "NaN" : v(r.dense_ms)) << ' '
             << (r.dense_from_single_update ? v(r.dense_ms) : "NaN") << '\n';
    }
    util::write_file_atomic(dir / "timing.csv", csv.str());
    // O(k n²) through the structured point nearest 200 landmarks
    double ref = 0;
    int ref_k = 0;
    for (const auto& r : rows)
        if (r.structured_ms > 0 && (ref_k == 0 || std::abs(r.landmarks - 200) < std::abs(ref_k - 200))) {
            ref_k = r.landmarks;
            ref = r.structured_ms;
        }
    std::ostringstream gp;
    gp << block("t", data.str()) << block("arm", "50 22 20\n100 170 130\n150 550 500\n200 1500 1300\n")
       << "set logscale xy\nset grid\nset key top left\nset xlabel 'landmarks k (all updated each step; state 3+2k)'\n"
       << "set ylabel 'time per step (ms)'\nset title 'EKF-SLAM update, worst case: k updates of a (3+2k)-state'\n"
       << "f(k) = " << ref << " * (k * (3 + 2*k)**2) / (" << ref_k << ".0 * (3 + 2*" << ref_k << ")**2)\n"
       << "plot $arm u 1:2 w lp pt 5 lc rgb 'black' t 'thesis Table 3, ARM Cortex-A9 866 MHz',"
       << " $arm u 1:3 w lp pt 4 dt 2 lc rgb 'black' t 'thesis Table 3, OpenMP 2 threads',"
       << " $t u 1:4 w lp pt 9 lc rgb 'red' t 'dense P=(I-KH)P, this machine, 1 core',"
       << " $t u 1:5 w lp pt 8 dt 2 lc rgb 'red' t 'dense P=(I-KH)P, k x one measured update',"
       << " $t u 1:3 w lp pt 11 lc rgb 'orange' t 'dense P=P-KZK^T, this machine',"
       << " $t u 1:2 w lp pt 7 lc rgb 'blue' t 'structured (5 columns, rank-2 update), this machine'";
    if (ref > 0) gp << ", [50:1000] f(x) dt 3 lc rgb 'blue' t 'O(k n^2) through structured'";
    gp << "\n";
    plot(dir / "timing.png", gp.str());
}

}  // namespace hc::slam
