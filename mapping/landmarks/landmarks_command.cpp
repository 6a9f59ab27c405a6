// landmarks_command.cpp: see landmarks_command.hpp.
#include "mapping/landmarks/landmarks_command.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "model/harris/formats_json.hpp"
#include "mapping/landmarks/landmarks.hpp"
#include "mapping/landmarks/landmarks_job.hpp"

namespace fs = std::filesystem;

namespace hc::landmarks {

namespace {

/// The re-observation study: its table on stdout and in <out>/reobservation.md and .csv.
void run_reobservation(const LandmarksCommand& o) {
    ReobservationOptions ro;
    const auto dets = util::split_csv(o.corners);
    if (dets.size() != 1) throw InputError("--reobservation takes one corner source (--corners)");
    ro.detector = parse_detector(dets[0]);
    if (o.descriptor_given) {
        ro.descriptors.clear();
        for (const auto& s : util::split_csv(o.descriptor)) ro.descriptors.push_back(parse_descriptor(s));
    }
    ro.grid = {o.g, o.h};
    validate(ro.grid);
    ro.corners.formats = (o.config.empty() ? Formats{} : formats_from_file(o.config));
    fs::path root;
    const Dataset ds = open_dataset(o.source, root);
    std::fprintf(stderr, "landmarks: re-observations over %zu consecutive left images of %s...\n", ds.pairs.size(),
                 ds.name.c_str());
    const auto rows = reobservation_study(ds, ro);
    const ReobservationReport rep = reobservation_report(ds, ro, rows);
    fs::create_directories(o.out);
    write_atomic(fs::path(o.out) / "reobservation.md", rep.markdown);
    write_atomic(fs::path(o.out) / "reobservation.csv", rep.csv);
    std::printf("%s", rep.markdown.c_str());
}

/// The comparison's detectors, descriptors, grid, matcher and corner options from the flags.
ComparisonOptions comparison_options(const LandmarksCommand& o) {
    ComparisonOptions co;   // the thesis's comparison by default (--compare)
    if (!o.compare) {
        co.detectors.clear();
        co.descriptors.clear();
        for (const auto& s : util::split_csv(o.corners)) co.detectors.push_back(parse_detector(s));
        for (const auto& s : util::split_csv(o.descriptor)) co.descriptors.push_back(parse_descriptor(s));
    }
    if (co.detectors.empty() || co.descriptors.empty()) throw InputError("--corners and --descriptor name at least one each");
    co.grid = {o.g, o.h};
    validate(co.grid);
    co.match.norm = parse_norm(o.norm);
    co.match.ratio = o.ratio;
    co.match.drop_ties = o.drop_ties;
    for (auto det : co.detectors)
        for (auto d : co.descriptors) check_combination(d, det, co.match.norm);
    if (o.sigma <= 0) throw InputError("--sigma must be positive");
    co.corners.formats = (o.config.empty() ? Formats{} : formats_from_file(o.config));
    co.corners.progress = true;
    co.threads = o.threads;
    co.progress = [](const std::string& line) { std::fprintf(stderr, "landmarks: %s\n", line.c_str()); };
    return co;
}

/// The comparison's rows run in shards (the run directory: --run-dir, or <out>/run); none when
/// the shards are not all done.
std::optional<std::vector<ComparisonRow>> sharded_rows(const LandmarksCommand& o, const Dataset& ds, const fs::path& root,
                                                       const ComparisonOptions& co, const cluster::JobRunner& runner) {
    if (o.study) throw InputError("--study runs in one process: leave out " + cluster::sharding_flags_named());
    if (o.source.rig.given())
        throw InputError("--calib (a rig's pairs) runs in one process: leave out " + cluster::sharding_flags_named());
    LandmarksJob p;
    p.dataset = o.source.dataset;
    p.root = root;
    p.need_truth = o.source.need_truth;
    p.sequence = o.source.sequence;
    if (o.source.dataset == "kitti") {
        const util::Range r = util::parse_range(o.source.pairs, "--pairs");
        p.first = r.first;
        p.last = r.first + static_cast<int>(ds.pairs.size());
    }
    p.options = co;
    p.pairs = ds.pairs.size();
    p.shards = runner.settings().shards;
    const cluster::Manifest m = landmarks_manifest(p);
    const auto merged = runner.run(m, o.out);
    if (!merged) return std::nullopt;
    return landmarks_rows(*merged);
}

}  // namespace

void run_landmarks_command(const LandmarksCommand& o, const cluster::JobRunner& runner) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::function<double()> secs = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    if (o.reobservation) {
        if (o.compare || o.study || runner.sharded() || o.source.rig.given())
            throw InputError("--reobservation runs alone: leave out --compare, --study, --calib and " +
                             cluster::sharding_flags_named());
        run_reobservation(o);
        return;
    }
    const ComparisonOptions co = comparison_options(o);
    std::fprintf(stderr, "landmarks: loading %s...\n", o.source.rig.given() ? o.source.rig.calib.c_str() : o.source.dataset.c_str());
    fs::path root;
    const Dataset ds = open_dataset(o.source, root);
    std::fprintf(stderr, "landmarks: %s, %zu pairs\n", ds.name.c_str(), ds.pairs.size());
    fs::create_directories(o.out);

    std::vector<std::vector<PairKeypoints>> kps;
    std::vector<ComparisonRow> rows;
    if (runner.sharded()) {
        auto merged = sharded_rows(o, ds, root, co, runner);
        if (!merged) return;
        rows = std::move(*merged);
    } else {
        rows = compare(ds, co, &kps);
    }
    ReportOptions ro;
    ro.out = o.out;
    ro.sigma_px = o.sigma;
    ro.landmark_files = o.landmark_files;
    ro.overlays = o.overlays;
    ro.study = o.study;
    ro.corrected = o.corrected;
    ro.threads = o.threads;
    ro.calib = o.source.rig.calib;
    ro.config = o.config;
    const auto rep = write_comparison_report(ds, co, rows, kps, ro, secs);
    std::printf("%s", comparison_markdown(rows).c_str());
    std::printf("landmarks: comparison %.1f s, total %.1f s; report %s\n", rep.compare_seconds, rep.total_seconds,
                (fs::path(o.out) / "report.md").c_str());
}

}  // namespace hc::landmarks
