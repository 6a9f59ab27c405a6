// sweep_report.cpp: see sweep_report.hpp.
#include "sweep/sweep_report.hpp"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "model/harris/formats_json.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace hc::sweep {

namespace {

std::string trust_cell(const TrustResult& t) {
    if (!t.ran) return "-";
    if (t.failed == 0) return fmt::format("{} mism. ({} run{}{})", t.mismatches, t.runs, t.runs == 1 ? "" : "s", t.cached ? ", cached" : "");
    return fmt::format("**{} FAILED**, {} mism.", t.failed, t.mismatches);
}

std::string gate_cell(const TrustResult& t) {
    if (!t.ran) return "-";
    if (t.failed == 0) return fmt::format("pass ({:.0f} s{})", t.seconds, t.cached ? ", recorded" : "");
    return "**" + t.detail.substr(0, t.detail.find(':', t.detail.find(':') + 1)) + "**";
}

double pct(double a, double b) { return b ? 100.0 * (a - b) / b : 0.0; }

std::string stages_cell(const PointResult& p) {
    if (!p.has_stages) return "not run";
    return p.stages.column() + (p.stages.cached ? " (cached)" : "");
}

std::string ranges_cell(const PointResult& p) {
    if (!p.has_ranges) return "-";
    const std::string routes = " (" + p.ranges.routes() + ")";
    switch (p.ranges.overall()) {
        case Verdict::proven: return "proven safe" + routes;
        case Verdict::wraps: {
            const RegisterRange& w = *p.ranges.first_wrap();
            return fmt::format("**wraps at {}** (witnesses/{}.pgm){}", kRegNames[static_cast<int>(w.reg)],
                               witness_stem(p.config.name, w.reg), routes);
        }
        default: return p.ranges.summary() + routes;
    }
}

}  // namespace

VerilatorTrust verilator_trust(const PointResult& p) {
    return vl::netlist_trust(p.gate.ran || p.verilator.ran, (p.gate.ran && p.gate.failed) || (p.verilator.ran && p.verilator.failed),
                             p.has_stages && p.stages.all_proven());
}

Findings findings(const SweepResult& r) {
    Findings f;
    const auto& P = r.points;
    for (size_t i = 0; i < P.size(); ++i)
        if (P[i].config.formats == Formats{}) f.thesis = static_cast<int>(i);
    if (f.thesis < 0) return f;
    const PointResult& T = P[f.thesis];
    for (size_t i = 0; i < P.size(); ++i) {
        const PointResult& p = P[i];
        if (p.wraps || static_cast<int>(i) == f.thesis) continue;
        if (p.accuracy.recall() >= T.accuracy.recall() && p.accuracy.precision() >= T.accuracy.precision() &&
            (p.cost.luts < T.cost.luts || p.cost.dsps < T.cost.dsps) && p.cost.dsps <= T.cost.dsps) {
            if (f.cheapest_as_good < 0 ||
                std::pair(p.cost.luts, p.cost.dsps) < std::pair(P[f.cheapest_as_good].cost.luts, P[f.cheapest_as_good].cost.dsps))
                f.cheapest_as_good = static_cast<int>(i);
        }
        if (p.cost.luts <= T.cost.luts && p.cost.dsps <= T.cost.dsps && p.accuracy.f1() > T.accuracy.f1()) {
            if (f.best_at_thesis_cost < 0 || p.accuracy.f1() > P[f.best_at_thesis_cost].accuracy.f1())
                f.best_at_thesis_cost = static_cast<int>(i);
        }
    }
    return f;
}

std::string to_csv(const SweepResult& r) {
    // the formats columns are the rows of format_fields(), in its order
    std::string s = "name,";
    for (const auto& fld : format_fields()) s.append(fld.name).append(",");
    s +=
        "recall,precision,f1,tp,fp,fn,luts,inv,ffs,dsps,carry4,muxf,srl,register_bits,wraps,"
        "wrap_sobel,wrap_m_resize,wrap_block_sum,wrap_k_term,wrap_response,pareto,"
        "rtl_runs,rtl_failed,rtl_mismatches,verilator_runs,verilator_failed,verilator_mismatches,synth_seconds,"
        "landmark_keypoints,landmark_matches,landmark_correct,landmark_truth_known,landmark_truth_correct,"
        "gate_passed,gate_seconds,ranges,ranges_first_wrap,"
        "trajectory_ape_slam,trajectory_ape_odometry,trajectory_path_length,trajectory_odometry_failures,"
        "stages_proven,stages_not_proven,verilator_trust\n";
    for (const auto& p : r.points) {
        const Formats& f = p.config.formats;
        s += p.config.name + ",";
        for (const auto& fld : format_fields()) s += fmt::format("{},", f.*(fld.member));
        s += fmt::format("{:.6f},{:.6f},{:.6f},{},{},{},", p.accuracy.recall(), p.accuracy.precision(), p.accuracy.f1(),
                         p.accuracy.tp, p.accuracy.fp, p.accuracy.fn);
        s += fmt::format("{},{},{},{},{},{},{},{},{},", p.cost.luts, p.cost.inv, p.cost.ffs, p.cost.dsps, p.cost.carry4,
                         p.cost.muxf, p.cost.srl, p.register_bits, p.wraps ? 1 : 0);
        for (int k = 0; k < stage_count; ++k) s += fmt::format("{},", p.overflow.wrapped[k]);
        s += fmt::format("{},", p.pareto ? 1 : 0);
        auto tr = [](const TrustResult& t) { return t.ran ? fmt::format("{},{},{},", t.runs, t.failed, t.mismatches) : std::string(",,,"); };
        s += tr(p.rtl) + tr(p.verilator);
        s += fmt::format("{:.1f},", p.cost.seconds);
        const landmarks::Totals& l = p.landmarks;
        s += p.has_landmarks ? fmt::format("{},{},{},{},{},", l.keypoints, l.all, l.correct, l.truth_known, l.truth_correct)
                             : std::string(",,,,,");
        s += p.gate.ran ? fmt::format("{},{:.1f},", p.gate.failed == 0 ? 1 : 0, p.gate.seconds) : std::string(",,");
        const RegisterRange* fw = p.has_ranges ? p.ranges.first_wrap() : nullptr;
        s += fmt::format("{},{},", p.has_ranges ? verdict_name(p.ranges.overall()) : "",
                         fw ? kRegNames[static_cast<int>(fw->reg)] : "");
        const Trajectory& t = p.trajectory;
        s += p.has_trajectory ? fmt::format("{:.6f},{:.6f},{:.6f},{},", t.ape_slam, t.ape_odometry, t.path_length,
                                            t.odometry_failures)
                              : std::string(",,,,");
        std::string proven, not_proven;   // empty: not run; the stages not proven as name:verdict, ';'-separated
        if (p.has_stages) {
            int n = 0;
            for (const StageProof& sp : p.stages.stages) {
                if (sp.verdict == EqVerdict::equal) ++n;
                else not_proven += fmt::format("{}{}:{}", not_proven.empty() ? "" : ";", kEqStageNames[static_cast<int>(sp.stage)],
                                               eq_verdict_name(sp.verdict));
            }
            proven = std::to_string(n);
        }
        s += fmt::format("{},{},{}\n", proven, not_proven, vl::netlist_trust_name(verilator_trust(p)));
    }
    return s;
}

void to_json(json& j, const Trajectory& t) {
    j = {{"ape_slam_m", t.ape_slam}, {"ape_odometry_m", t.ape_odometry}, {"path_length_m", t.path_length},
         {"frames", t.frames}, {"odometry_failures", t.odometry_failures}};
}

void from_json(const json& j, Trajectory& t) {
    t.ape_slam = j.at("ape_slam_m");
    t.ape_odometry = j.at("ape_odometry_m");
    t.path_length = j.at("path_length_m");
    t.frames = j.at("frames");
    t.odometry_failures = j.at("odometry_failures");
}

/// What the stage proofs and Verilator trust columns mean.
std::string stages_markdown(const SweepResult& r) {
    const bool any = std::any_of(r.points.begin(), r.points.end(), [](const PointResult& p) { return p.has_stages; });
    std::string s = "Stage proofs (docs/stage-equivalence.md): each datapath entity's netlist (sobel_x, sobel_y, m_products, "
                    "block_filter, harris_response, threshold, find_max, local_maximum), synthesised by GHDL at the "
                    "configuration's generics, proven equal to the model's stage function for every input of its domain "
                    "(z3, then cvc5), or the verdicts that are not *proven*; \"cached\": proven by an earlier run for the same "
                    "synthesis key. ";
    s += any ? "Run with `--stage-proofs`; a configuration without them says *not run*.\n\n"
             : "Not run (`--stage-proofs` runs them): no configuration is stage-proven.\n\n";
    s += "Verilator trust: *stages proven* when the gate and the Verilator runs passed and every stage is proven, so the "
         "netlist's datapath stages are faithful for every input; the control (control_shift_register's stage enables), "
         "load_control, the input converters that form the windows, corner_shift_register and harris_top's wiring of the "
         "stages are not stage-proven and are checked on the streams run only; *samples only* when they passed without every stage "
         "proven (the gate's lock step against GHDL and the model, and the KITTI pairs, are samples); *failed* when the gate "
         "or a run failed; *-* when neither ran. No configuration is claimed equivalent as a whole design.\n\n";
    return s;
}

/// The trajectory column's table (a line saying why it is absent when no point has one).
std::string trajectory_markdown(const SweepResult& r) {
    if (std::none_of(r.points.begin(), r.points.end(), [](const PointResult& p) { return p.has_trajectory; }))
        return fmt::format("\nTrajectory downstream: {}.\n", r.trajectory_run);
    std::string s = fmt::format("\nTrajectory downstream (APE: translation RMSE against the poses, no alignment): {}.\n\n"
                                "| configuration | F1 | wraps | APE EKF-SLAM (m) | % of path | APE visual odometry alone (m) | "
                                "odometry failures |\n|---|---:|---|---:|---:|---:|---:|\n",
                                r.trajectory_run);
    for (const auto& p : r.points) {
        if (!p.has_trajectory) continue;
        const Trajectory& t = p.trajectory;
        s += fmt::format("| {} | {:.4f} | {} | {:.3f} | {:.2f} | {:.3f} | {} |\n", p.config.name, p.accuracy.f1(),
                         p.wraps ? "yes" : "no", t.ape_slam, t.ape_percent(), t.ape_odometry, t.odometry_failures);
    }
    return s;
}

std::string to_markdown(const SweepResult& r) {
    std::string s = fmt::format("# Bit-width sweep \"{}\"\n\nCommand: `{}`\n\n", r.spec.name, r.command);
    s += fmt::format("Accuracy: spec model against OpenCV's cornerHarris (docs/metrics.md) on {}; {} frames scored "
                     "(the first stereo pair only seeds the threshold).\n\n", r.stream, r.scored_frames);
    s += fmt::format("Cost: yosys `synth_xilinx` of harris_top (OBSERVE=false, IMG {}x{}), GHDL's Verilog with signed "
                     "multiplies restored (docs/bit-widths.md); LUT = LUT1..LUT6, INV cells not included.\n\n",
                     r.spec.cost_geometry.width, r.spec.cost_geometry.height);
    s += fmt::format("Pareto front: minimum LUTs and DSPs, maximum F1, among configurations that do not wrap (marked **P**). "
                     "RTL checks (the Pareto points, the thesis and the findings below): GHDL co-simulation of "
                     "{} (mismatching cycles, every inter-stage register compared after every cycle) and ", r.regression_set);
    s += r.spec.trust.verilator_pairs.empty()
             ? std::string("no Verilator run")
             : fmt::format("Verilator on KITTI {} pairs {} (mismatching writes; reads compared)", r.spec.sequence,
                           r.spec.trust.verilator_pairs);
    s += r.spec.trust.verilator_gate
             ? "; the Gate column is verilate's three-way gate (GHDL simulation of the VHDL, Verilator on GHDL's "
               "netlist, the cycle model on small frames; docs/verilator.md) with its wall time (\"recorded\": the "
               "verdict of an earlier run for the same formats, sources and tools).\n\n"
             : "; no three-way gate (trust.verilator_gate false): the netlist is checked against the model, not "
               "against GHDL.\n\n";
    s += fmt::format("Stereo matches downstream (columns *stereo correct*: pass the cross-check, ratio and epipolar tests; "
                     "*GT-correct*: of those, within 1 px of the ground-truth disparity): {}.\n\n", r.landmark_pairs);
    s += "Ranges (every input, docs/derived-ranges.md): *proven safe* when no register can wrap; *wraps at R* with "
         "the pixel window (witnesses/) that wraps register R; *open* with the bound and the values the witness search "
         "reached. In brackets, how many registers each route decided (interval bound, witness search, z3 on the "
         "model's arithmetic, z3 on GHDL's netlist) and the netlist route's verdicts. The P column says whether a "
         "Pareto point is proven.\n\n";
    s += stages_markdown(r);
    s += "| configuration | recall | precision | F1 | stereo correct | GT-correct | LUT | FF | DSP | CARRY4 | reg. bits | wraps | ranges | P | GHDL | Gate | Verilator | stage proofs | Verilator trust |\n"
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|:-:|---|---|---|---|---|\n";
    for (const auto& p : r.points) {
        const std::string lc = p.has_landmarks ? std::to_string(p.landmarks.correct) : "-";
        const std::string lt = p.has_landmarks ? std::to_string(p.landmarks.truth_correct) : "-";
        const std::string pc = !p.pareto ? "" : p.has_ranges && p.ranges.overall() == Verdict::proven ? "**P** proven" : "**P** not proven";
        s += fmt::format("| {} | {:.4f} | {:.4f} | {:.4f} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                         p.config.name, p.accuracy.recall(), p.accuracy.precision(), p.accuracy.f1(), lc, lt, p.cost.luts, p.cost.ffs,
                         p.cost.dsps, p.cost.carry4, p.register_bits, p.wraps ? "**" + p.overflow.summary() + "**" : std::string("none"),
                         ranges_cell(p), pc, trust_cell(p.rtl), gate_cell(p.gate), trust_cell(p.verilator), stages_cell(p),
                         vl::netlist_trust_name(verilator_trust(p)));
    }
    s += trajectory_markdown(r);
    const Findings f = findings(r);
    if (f.thesis >= 0) {
        const auto& T = r.points[f.thesis];
        s += fmt::format("\nThesis configuration: recall {:.4f}, precision {:.4f}, F1 {:.4f}; {} LUT, {} FF, {} DSP",
                         T.accuracy.recall(), T.accuracy.precision(), T.accuracy.f1(), T.cost.luts, T.cost.ffs, T.cost.dsps);
        if (T.has_cost_ghdl)
            s += fmt::format(" (GHDL's Verilog as emitted: {} LUT, {} FF, {} DSP)", T.cost_ghdl.luts, T.cost_ghdl.ffs, T.cost_ghdl.dsps);
        s += ".\n\n";
        if (f.cheapest_as_good >= 0) {
            const auto& C = r.points[f.cheapest_as_good];
            s += fmt::format("Cheapest configuration with recall and precision >= the thesis's: **{}** ({:.4f} / {:.4f}); "
                             "{} LUT ({:+.1f} %), {} FF ({:+.1f} %), {} DSP ({:+d}), {} register bits ({:+d}).\n\n",
                             C.config.name, C.accuracy.recall(), C.accuracy.precision(), C.cost.luts, pct(C.cost.luts, T.cost.luts),
                             C.cost.ffs, pct(C.cost.ffs, T.cost.ffs), C.cost.dsps, static_cast<int>(C.cost.dsps - T.cost.dsps),
                             C.register_bits, static_cast<int>(C.register_bits - T.register_bits));
        } else {
            s += "No configuration is cheaper than the thesis's with recall and precision at least as high.\n\n";
        }
        if (f.best_at_thesis_cost >= 0) {
            const auto& B = r.points[f.best_at_thesis_cost];
            s += fmt::format("Most accurate configuration at no more than the thesis's LUTs and DSPs: **{}**, F1 {:.4f} "
                             "(recall {:.4f}, precision {:.4f}); {} LUT, {} DSP.\n\n",
                             B.config.name, B.accuracy.f1(), B.accuracy.recall(), B.accuracy.precision(), B.cost.luts, B.cost.dsps);
        } else {
            s += "No configuration at or below the thesis's LUTs and DSPs has a higher F1.\n\n";
        }
    }
    s += "Timing: ";
    s += fmt::format("frames {:.1f} s, OpenCV reference {:.1f} s, cost {:.1f} s ({} synthesised, {} from the cache; "
                     "{:.0f} s of synthesis wall time summed), accuracy + overflow audit {:.1f} s, stereo matches {:.1f} s, "
                     "trajectories {:.1f} s, "
                     "RTL checks {:.1f} s (three-way gates: {} run, {:.0f} s of wall time summed, {} verdicts recorded earlier); "
                     "total {:.1f} s.\n",
                     r.seconds_load, r.seconds_reference, r.seconds_cost, r.synthesised, r.synth_cached, r.synth_seconds_sum,
                     r.seconds_accuracy, r.seconds_landmarks, r.seconds_trajectory, r.seconds_trust, r.gates_run, r.gate_seconds_sum, r.gates_cached,
                     r.seconds_total);
    for (const auto& n : r.spec.notes) s += "\nNote: " + n + ".\n";
    return s;
}

std::string to_json(const SweepResult& r) {
    json pts = json::array();
    for (const auto& p : r.points) {
        json ovf = json::object();
        for (int k = 0; k < stage_count; ++k)
            ovf[kStageNames[k]] = {{"wrapped", p.overflow.wrapped[k]}, {"sign_lost", p.overflow.sign_lost[k]}, {"values", p.overflow.values[k]}};
        auto cost = [](const Cost& c) {   // Cost's JSON, its time named synth_seconds
            json j = c;
            j["synth_seconds"] = j.at("seconds");
            j.erase("seconds");
            return j;
        };
        auto trust = [](const TrustResult& t) {
            return t.ran ? json{{"runs", t.runs}, {"failed", t.failed}, {"mismatches", t.mismatches}, {"reads", t.reads},
                                {"seconds", t.seconds}, {"cached", t.cached}, {"detail", t.detail}}
                         : json(nullptr);
        };
        json j = {{"name", p.config.name},
                  {"formats", json::parse(formats_to_json(p.config.formats))},
                  {"recall", p.accuracy.recall()}, {"precision", p.accuracy.precision()}, {"f1", p.accuracy.f1()},
                  {"confusion", {{"tp", p.accuracy.tp}, {"tn", p.accuracy.tn}, {"fp", p.accuracy.fp}, {"fn", p.accuracy.fn}}},
                  {"cost", cost(p.cost)}, {"register_bits", p.register_bits}, {"wraps", p.wraps}, {"overflow", ovf},
                  {"pareto", p.pareto}, {"rtl", trust(p.rtl)}, {"gate", trust(p.gate)}, {"verilator", trust(p.verilator)},
                  {"eval_seconds", p.eval_seconds}, {"overflow_seconds", p.overflow_seconds}};
        j["ranges"] = p.has_ranges ? range_report_to_json(p.ranges) : json(nullptr);
        j["stages"] = p.has_stages ? stage_equivalence_to_json(p.stages) : json(nullptr);
        if (p.has_stages) j["stages"]["cached"] = p.stages.cached;
        j["verilator_trust"] = vl::netlist_trust_name(verilator_trust(p));
        if (p.has_cost_ghdl) j["cost_ghdl_verilog"] = cost(p.cost_ghdl);
        const landmarks::Totals& l = p.landmarks;
        j["landmarks"] = p.has_landmarks ? json{{"keypoints", l.keypoints}, {"matches", l.all}, {"correct", l.correct},
                                                {"truth_known", l.truth_known}, {"truth_correct", l.truth_correct},
                                                {"pairs", l.pairs}}
                                         : json(nullptr);
        j["trajectory"] = p.has_trajectory ? json(p.trajectory) : json(nullptr);
        pts.push_back(j);
    }
    json j = {{"name", r.spec.name}, {"command", r.command}, {"stream", r.stream}, {"scored_frames", r.scored_frames},
              {"landmark_pairs", r.landmark_pairs}, {"trajectory_run", r.trajectory_run},
              {"cost_geometry", {{"width", r.spec.cost_geometry.width}, {"height", r.spec.cost_geometry.height}}},
              {"points", pts}, {"notes", r.spec.notes},
              {"seconds", {{"load", r.seconds_load}, {"reference", r.seconds_reference}, {"cost", r.seconds_cost},
                           {"accuracy", r.seconds_accuracy}, {"landmarks", r.seconds_landmarks},
                           {"trajectory", r.seconds_trajectory}, {"trust", r.seconds_trust}, {"total", r.seconds_total}}},
              {"synthesised", r.synthesised}, {"synth_cached", r.synth_cached}, {"synth_seconds_sum", r.synth_seconds_sum},
              {"gates_run", r.gates_run}, {"gates_cached", r.gates_cached}, {"gate_seconds_sum", r.gate_seconds_sum}};
    return j.dump(2) + "\n";
}

std::string write_plot(const SweepResult& r, const fs::path& dir) {
    // y ranges from the non-wrapping points only: a wrapping point's accuracy can be near 0
    // and would squash the front into one line; such points are drawn clamped to the
    // bottom of the axis (their true values are in the table). Every axis is framed on its
    // data with a margin (util::axis_range).
    std::vector<double> acc[3], luts, dsps;
    for (const auto& p : r.points) {
        luts.push_back(p.cost.luts);
        dsps.push_back(p.cost.dsps);
        if (!p.wraps) {
            acc[0].push_back(p.accuracy.f1());
            acc[1].push_back(p.accuracy.recall());
            acc[2].push_back(p.accuracy.precision());
        }
    }
    util::AxisRange yr[3];
    double ymin[3];
    for (int k = 0; k < 3; ++k) {
        yr[k] = util::axis_range(acc[k], 0.12, 0.0, 1e300, 0.004);
        ymin[k] = yr[k].lo;
    }
    const util::AxisRange xr_luts = util::axis_range(luts, 0.06, 0.0, 1e300, 2.0),
                          xr_dsps = util::axis_range(dsps, 0.06, 0.0, 1e300, 2.0);
    // data: one file per class (ok, Pareto, wrapping) so gnuplot styles them apart
    std::string ok, par, wrap;
    for (const auto& p : r.points) {
        double v[3] = {p.accuracy.f1(), p.accuracy.recall(), p.accuracy.precision()};
        if (p.wraps)
            for (int k = 0; k < 3; ++k) v[k] = std::max(v[k], ymin[k] + 0.001);
        const std::string line = fmt::format("{} {} {:.6f} {:.6f} {:.6f} \"{}\"\n", p.cost.luts, p.cost.dsps, v[0], v[1], v[2],
                                             p.config.name);
        (p.wraps ? wrap : p.pareto ? par : ok) += line;
    }
    const fs::path tmp = dir / ".plot";
    fs::create_directories(tmp);
    std::ofstream(tmp / "ok.dat") << (ok.empty() ? "NaN NaN NaN NaN NaN \"\"\n" : ok);
    std::ofstream(tmp / "pareto.dat") << (par.empty() ? "NaN NaN NaN NaN NaN \"\"\n" : par);
    std::ofstream(tmp / "wrap.dat") << (wrap.empty() ? "NaN NaN NaN NaN NaN \"\"\n" : wrap);
    const fs::path png = tmp / "pareto.png";
    std::string g = "set terminal pngcairo size 1600,1000 font 'sans,10'\n";
    g += "set output '" + png.string() + "'\n";
    g += "set multiplot layout 2,2 title 'Bit-width sweep " + r.spec.name + ": accuracy against OpenCV vs yosys synth\\_xilinx cost'\n";
    g += "set grid\nset key outside bottom center horizontal\n";
    const std::string d = tmp.string() + "/";
    auto panel = [&](const std::string& xcol, const std::string& xlabel, const std::string& ycol, const std::string& ylabel, bool labels) {
        const util::AxisRange& y = yr[ycol == "3" ? 0 : ycol == "4" ? 1 : 2];
        std::string p = "set xlabel '" + xlabel + "'\nset ylabel '" + ylabel + "'\n";
        p += "set yrange " + y.gnuplot() + "\nset xrange " + (xcol == "1" ? xr_luts : xr_dsps).gnuplot() + "\n";
        p += "plot '" + d + "ok.dat' using " + xcol + ":" + ycol + " with points pt 6 ps 1.2 lc rgb '#777777' title 'dominated', \\\n";
        p += "     '" + d + "pareto.dat' using " + xcol + ":" + ycol + " with points pt 7 ps 1.6 lc rgb '#d62728' title 'Pareto-optimal', \\\n";
        p += "     '" + d + "wrap.dat' using " + xcol + ":" + ycol + " with points pt 2 ps 1.4 lc rgb '#1f77b4' title 'wraps (excluded; at the axis if below it)'";
        if (labels) p += ", \\\n     '" + d + "pareto.dat' using " + xcol + ":" + ycol + ":6 with labels offset 0,1 font 'sans,7' notitle";
        return p + "\n";
    };
    g += panel("1", "LUTs", "3", "F1", true);
    g += panel("2", "DSP48E1", "3", "F1", false);
    g += panel("1", "LUTs", "4", "recall", false);
    g += panel("1", "LUTs", "5", "precision", false);
    g += "unset multiplot\n";
    std::ofstream(tmp / "plot.gp") << g;
    int rc = 127;
    try {
        rc = util::run_process({"gnuplot", (tmp / "plot.gp").string()}, {.log = tmp / "gnuplot.log"});
    } catch (const SimulatorError&) {   // not installed: rc stays 127
    }
    if (rc != 0 || !fs::exists(png)) return fmt::format("gnuplot failed (status {}), see {}", rc, (tmp / "gnuplot.log").string());
    fs::rename(png, dir / "pareto.png");   // same directory tree: atomic
    fs::remove_all(tmp);
    return "";
}

void write_reports(const SweepResult& r, const fs::path& dir) {
    fs::create_directories(dir);
    util::write_file_atomic(dir / "sweep.csv", to_csv(r));
    util::write_file_atomic(dir / "sweep.json", to_json(r));
    util::write_file_atomic(dir / "sweep.md", to_markdown(r));
    for (const auto& p : r.points)   // the windows that wrap a register, as images (ranges.hpp)
        if (const RegisterRange* w = p.has_ranges ? p.ranges.first_wrap() : nullptr)
            util::write_file_atomic(dir / "witnesses" / (witness_stem(p.config.name, w->reg) + ".pgm"), pgm_bytes(witness_image(w->witness)));
    if (const std::string e = write_plot(r, dir); !e.empty()) std::fprintf(stderr, "sweep: warning: no plot: %s\n", e.c_str());
}

}  // namespace hc::sweep
