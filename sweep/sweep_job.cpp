// sweep_job.cpp: the job kinds "sweep" and "sweep-check" (sweep_job.hpp).
#include "sweep/sweep_job.hpp"

#include <cstdio>
#include <string>

#include "model/harris/formats_json.hpp"
#include "model/util/util.hpp"

namespace hc::sweep {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

template <class A>
json array_json(const A& a) {
    return json(std::vector<std::uint64_t>(a.begin(), a.end()));
}

template <class A>
void array_from(const json& j, A& a) {
    if (j.size() != a.size()) throw hc::InputError("sweep: an overflow count list has the wrong length");
    for (std::size_t k = 0; k < a.size(); ++k) a[k] = j.at(k).get<std::uint64_t>();
}

json point_json(const PointResult& p) {
    json j = {{"name", p.config.name},
              {"formats", json::parse(formats_to_json(p.config.formats))},
              {"overflow", {{"wrapped", array_json(p.overflow.wrapped)}, {"sign_lost", array_json(p.overflow.sign_lost)},
                            {"values", array_json(p.overflow.values)}}},
              {"confusion", {{"tp", p.accuracy.tp}, {"tn", p.accuracy.tn}, {"fp", p.accuracy.fp}, {"fn", p.accuracy.fn}}},
              {"cost", json(p.cost)},
              {"register_bits", p.register_bits},
              {"wraps", p.wraps},
              {"eval_seconds", p.eval_seconds},
              {"overflow_seconds", p.overflow_seconds}};
    if (p.has_cost_ghdl) j["cost_ghdl"] = json(p.cost_ghdl);
    if (p.has_ranges) j["ranges"] = range_report_to_json(p.ranges);
    if (p.has_stages) {
        j["stages"] = stage_equivalence_to_json(p.stages);
        j["stages"]["cached"] = p.stages.cached;
    }
    if (p.has_landmarks) j["landmarks"] = p.landmarks;
    if (p.has_trajectory) j["trajectory"] = json(p.trajectory);
    return j;
}

PointResult point_from(const json& j) {
    PointResult p;
    p.config.name = j.at("name");
    p.config.formats = formats_from_json(j.at("formats"), "sweep shard result, configuration " + p.config.name);
    array_from(j.at("overflow").at("wrapped"), p.overflow.wrapped);
    array_from(j.at("overflow").at("sign_lost"), p.overflow.sign_lost);
    array_from(j.at("overflow").at("values"), p.overflow.values);
    const json& c = j.at("confusion");
    p.accuracy.tp = c.at("tp");
    p.accuracy.tn = c.at("tn");
    p.accuracy.fp = c.at("fp");
    p.accuracy.fn = c.at("fn");
    p.cost = j.at("cost").get<Cost>();
    p.register_bits = j.at("register_bits");
    p.wraps = j.at("wraps");
    p.eval_seconds = j.at("eval_seconds");
    p.overflow_seconds = j.at("overflow_seconds");
    if (j.contains("cost_ghdl")) {
        p.cost_ghdl = j.at("cost_ghdl").get<Cost>();
        p.has_cost_ghdl = true;
    }
    if (j.contains("ranges")) {
        p.ranges = range_report_from_json(j.at("ranges"));
        p.ranges.formats = p.config.formats;
        p.has_ranges = true;
    }
    if (j.contains("stages")) {
        p.stages = stage_equivalence_from_json(j.at("stages"));
        p.stages.formats = p.config.formats;
        p.stages.cached = j.at("stages").value("cached", false);
        p.has_stages = true;
    }
    if (j.contains("landmarks")) {
        p.landmarks = j.at("landmarks").get<landmarks::Totals>();
        p.has_landmarks = true;
    }
    if (j.contains("trajectory")) {
        p.trajectory = j.at("trajectory").get<Trajectory>();
        p.has_trajectory = true;
    }
    return p;
}

json outcome_json(const CheckTask& t, const CheckOutcome& c) {
    return {{"point", t.point}, {"kind", check_kind_name(t.kind)}, {"stream", t.stream},
            {"status", c.status}, {"log", c.log.string()}, {"gate_cached", c.gate_cached},
            {"result", trust_to_json(c.one)}};
}

CheckOutcome outcome_from(const json& j) {
    CheckOutcome c;
    c.status = j.at("status");
    c.log = j.at("log").get<std::string>();
    c.gate_cached = j.at("gate_cached");
    c.one = trust_from_json(j.at("result"));
    return c;
}

// The options both sweep kinds' shards share: the KITTI root, the cache, accuracy threads.
SweepOptions shard_options(const json& common) {
    SweepOptions o;
    o.kitti = common.at("kitti").get<std::string>();
    o.cache = common.at("cache").get<std::string>();
    o.threads = common.at("threads");
    o.stage_proofs = common.value("stage_proofs", false);
    return o;
}

json stream_json(const util::RegressionStream& s) {
    return {{"pattern", s.pattern}, {"width", s.width}, {"height", s.height}, {"frames", s.frames},
            {"idle_every", s.idle_every}, {"image", s.image.string()}, {"breaks", s.breaks.string()}};
}

util::RegressionStream stream_from(const json& j) {
    util::RegressionStream s;
    s.pattern = j.at("pattern");
    s.width = j.at("width");
    s.height = j.at("height");
    s.frames = j.at("frames");
    s.idle_every = j.at("idle_every");
    s.image = j.at("image").get<std::string>();
    s.breaks = j.at("breaks").get<std::string>();
    return s;
}

}  // namespace

cluster::Manifest sweep_check_manifest(const std::string& spec_text, const std::string& spec_name,
                                       const SweepResult& r, const CheckPlan& plan,
                                       const SweepOptions& o) {
    cluster::Manifest m;
    m.job = "sweep-check";
    json streams = json::array();
    for (const auto& s : plan.streams) streams.push_back(stream_json(s));
    m.common = {{"spec", spec_text},
                {"spec_name", spec_name},
                {"spec_hash", util::hex64(util::fnv1a(spec_text))},
                {"kitti", fs::absolute(o.kitti).string()},
                {"cache", fs::absolute(o.cache).string()},
                {"out", fs::absolute(o.out).string()},
                {"backend", o.ghdl_backend},
                {"threads", o.threads},
                {"streams", streams}};
    for (const CheckTask& t : plan.tasks) {
        const PointResult& p = r.points.at(t.point);
        m.shards.push_back({{"point", t.point},
                            {"name", p.config.name},
                            {"formats", json::parse(formats_to_json(p.config.formats))},
                            {"key", plan.keys.at(t.point)},
                            {"kind", check_kind_name(t.kind)},
                            {"stream", t.stream}});
    }
    return m;
}

void apply_sweep_checks(SweepResult& r, const CheckPlan& plan, const json& merged,
                        const SweepOptions& o) {
    const json& outs = merged.at("outcomes");
    if (outs.size() != plan.tasks.size())
        throw hc::InputError("sweep-check: the merged data holds " + std::to_string(outs.size()) +
                                         " outcomes, the plan " + std::to_string(plan.tasks.size()) + " checks");
    for (std::size_t k = 0; k < outs.size(); ++k) {
        const CheckTask& t = plan.tasks[k];
        const json& j = outs[k];
        if (j.at("point").get<std::size_t>() != t.point || j.at("kind") != check_kind_name(t.kind) ||
            j.at("stream").get<int>() != t.stream)
            throw hc::InputError("sweep-check: outcome " + std::to_string(k) + " answers another check than the plan's");
        apply_check(r, plan, t, outcome_from(j), o);
    }
    finish_checks(r);
}

cluster::Manifest sweep_manifest(const SweepJob& p) {
    const SweepSpec spec = parse_sweep_spec(p.spec_text, p.spec_name);
    cluster::Manifest m;
    m.job = "sweep";
    m.common = {{"spec", p.spec_text},
                {"spec_name", p.spec_name},
                {"spec_hash", util::hex64(util::fnv1a(p.spec_text))},
                {"kitti", fs::absolute(p.kitti).string()},
                {"middlebury", p.middlebury.empty() ? std::string() : fs::absolute(p.middlebury).string()},
                {"cache", fs::absolute(p.cache).string()},
                {"threads", p.threads},
                {"jobs", p.jobs},
                {"stage_proofs", p.stage_proofs}};
    for (auto [a, b] : cluster::split_items(static_cast<long>(spec.configs.size()), p.shards))
        m.shards.push_back({{"first", a}, {"last", b}});
    return m;
}

SweepResult sweep_result(const cluster::Manifest& m, const json& merged) {
    SweepResult r;
    r.spec = parse_sweep_spec(m.common.at("spec"), m.common.at("spec_name"));
    for (const auto& j : merged.at("points")) r.points.push_back(point_from(j));
    if (r.points.size() != r.spec.configs.size())
        throw hc::InputError("sweep: the merged data holds " + std::to_string(r.points.size()) +
                                         " points, the spec " + std::to_string(r.spec.configs.size()));
    r.stream = merged.at("stream");
    // the phases' times summed over the shards (each shard loads the frames and computes the reference)
    r.seconds_load = merged.at("seconds").at("load");
    r.seconds_reference = merged.at("seconds").at("reference");
    r.seconds_cost = merged.at("seconds").at("cost");
    r.seconds_accuracy = merged.at("seconds").at("accuracy");
    r.scored_frames = merged.at("scored_frames");
    r.landmark_pairs = merged.at("landmark_pairs");
    r.seconds_landmarks = merged.at("seconds").at("landmarks");
    r.trajectory_run = merged.at("trajectory_run");
    r.seconds_trajectory = merged.at("seconds").at("trajectory");
    for (const auto& p : r.points)
        for (const Cost* c : {&p.cost, p.has_cost_ghdl ? &p.cost_ghdl : nullptr}) {
            if (!c) continue;
            if (c->cached) ++r.synth_cached;
            else {
                ++r.synthesised;
                r.synth_seconds_sum += c->seconds;
            }
        }
    mark_pareto(r.points);
    mark_verify(r);
    return r;
}

void add_sweep_job(cluster::JobRegistry& reg) {
    reg.add({"sweep",
            [](const json& common, const json& shard, std::size_t) {
                const SweepSpec spec = parse_sweep_spec(common.at("spec"), common.at("spec_name"));
                SweepOptions o = shard_options(common);
                o.middlebury = common.at("middlebury").get<std::string>();
                o.jobs = common.at("jobs");
                std::vector<std::size_t> which;
                for (long i = shard.at("first"); i < shard.at("last").get<long>(); ++i) which.push_back(i);
                const PointsRun pr = evaluate_points(spec, which, o);
                json points = json::array();
                for (const auto& p : pr.points) points.push_back(point_json(p));
                return json{{"stream", pr.stream},
                            {"scored_frames", pr.scored_frames},
                            {"landmark_pairs", pr.landmark_pairs},
                            {"trajectory_run", pr.trajectory_run},
                            {"points", points},
                            {"seconds", {{"load", pr.seconds_load}, {"reference", pr.seconds_reference},
                                         {"cost", pr.seconds_cost}, {"accuracy", pr.seconds_accuracy},
                                         {"landmarks", pr.seconds_landmarks}, {"trajectory", pr.seconds_trajectory}}}};
            },
            [](const json&, const std::vector<json>& data) {
                json points = json::array();
                json seconds = {{"load", 0.0},     {"reference", 0.0}, {"cost", 0.0},
                                {"accuracy", 0.0}, {"landmarks", 0.0}, {"trajectory", 0.0}};
                for (const auto& d : data) {
                    for (auto& [k, v] : seconds.items()) v = v.get<double>() + d.at("seconds").at(k).get<double>();
                    if (d.at("stream") != data.front().at("stream") || d.at("scored_frames") != data.front().at("scored_frames") ||
                        d.at("landmark_pairs") != data.front().at("landmark_pairs") ||
                        d.at("trajectory_run") != data.front().at("trajectory_run"))
                        throw hc::InputError(
                            "sweep: shards measured different streams, landmark pairs or trajectory runs");
                    for (const auto& p : d.at("points")) points.push_back(p);
                }
                return json{{"stream", data.empty() ? json("") : data.front().at("stream")},
                            {"scored_frames", data.empty() ? json(0) : data.front().at("scored_frames")},
                            {"landmark_pairs", data.empty() ? json("") : data.front().at("landmark_pairs")},
                            {"trajectory_run", data.empty() ? json("") : data.front().at("trajectory_run")},
                            {"points", points},
                            {"seconds", seconds}};
            }});
}

void add_sweep_check_job(cluster::JobRegistry& reg) {
    reg.add({"sweep-check",
            [](const json& common, const json& shard, std::size_t) {
                const SweepSpec spec = parse_sweep_spec(common.at("spec"), common.at("spec_name"));
                SweepOptions o = shard_options(common);
                o.out = common.at("out").get<std::string>();
                o.ghdl_backend = common.at("backend");
                std::vector<util::RegressionStream> streams;
                for (const auto& s : common.at("streams")) streams.push_back(stream_from(s));
                CheckTask t;
                t.point = shard.at("point");
                t.kind = check_kind_from_name(shard.at("kind"));
                t.stream = shard.at("stream");
                Config config;
                config.name = shard.at("name");
                config.formats = formats_from_json(shard.at("formats"), "sweep-check manifest, configuration " + config.name);
                CheckRunner runner(spec, o);
                const CheckOutcome c = runner.run(t, config, shard.at("key"), streams);
                std::printf("sweep-check: %s %s%s: %s (%.0f s%s)\n", config.name.c_str(), check_kind_name(t.kind),
                            t.kind == CheckKind::ghdl ? (" " + streams.at(t.stream).stem()).c_str() : "",
                            c.status.c_str(), c.one.seconds, c.one.cached ? ", cached" : "");
                return json{{"outcomes", json::array({outcome_json(t, c)})}};
            },
            [](const json&, const std::vector<json>& data) {
                json outs = json::array();
                for (const auto& d : data)
                    for (const auto& o : d.at("outcomes")) outs.push_back(o);
                return json{{"outcomes", outs}};
            }});
}

}  // namespace hc::sweep
