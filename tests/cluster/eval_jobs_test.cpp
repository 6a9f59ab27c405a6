// eval_jobs_test: the eval and verilate job kinds. The cycle model's state and the host
// driver's position restore exactly; a cycle run started at a checkpoint reports the serial
// run's frames; and every sharded run (local pool, or a Slurm job array with tag [slurm])
// merges to exactly the data of the same evaluation computed in one process.
//
// `eval_jobs_tests --make-standin DIR` writes the stand-in KITTI sequences 02 and 03 into
// DIR, `--make-standin DIR SEQ WxH PAIRS` one of that size (for the command-line tests). Runs whose tags name [kitti] exit 77 (skipped) without
// KITTI sequence 01.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "io/cluster/cluster.hpp"
#include "cosim/verilator/verilate_job.hpp"
#include "eval/eval_job.hpp"
#include "eval/sequences.hpp"
#include "io/frames/frames.hpp"
#include "tools/registry.hpp"
#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"
#include "tests/cluster/standin_kitti.hpp"

using namespace hc;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path g_kitti;   // KITTI root holding sequences/01 (tests tagged [kitti])

fs::path scratch(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("hc-eval-jobs-" + std::to_string(::getpid())) / name;
    fs::remove_all(d);
    return d;
}

/// Stand-in sequences 02 (7 pairs) and 03 (5 pairs), 96x40, in the KITTI layout.
void make_standin(const fs::path& root) {
    test::write_standin_sequence(root, "02", 96, 40, 7, Pattern::blocks, 1);
    test::write_standin_sequence(root, "03", 96, 40, 5, Pattern::blocks, 7);
}

const fs::path& standin() {
    static const fs::path root = [] {
        fs::path r = scratch("standin");
        make_standin(r);
        return r;
    }();
    return root;
}

// An evaluation of `source` over the stand-in's `sequences`, one thread a shard.
eval::EvalJob standin_job(std::vector<std::string> sequences, const std::string& source, bool ablation) {
    eval::EvalJob j;
    j.kitti = standin();
    j.sequences = std::move(sequences);
    j.source = source;
    j.ablation = ablation;
    j.threads = 1;
    return j;
}

// The manifests of `j` in as few shards as it splits into and in `shards` shards.
std::pair<cluster::Manifest, cluster::Manifest> single_and_sharded(eval::EvalJob j, int shards) {
    j.shards = 0;
    cluster::Manifest single = eval::eval_manifest(j);
    j.shards = shards;
    return {std::move(single), eval::eval_manifest(j)};
}

eval::Stream pattern_stream(int w, int h, int frames) {
    eval::Stream s;
    for (int k = 0; k < frames; ++k) {
        s.frames.push_back(make_pattern(Pattern::blocks, w, h, k));
        s.names.push_back("p/" + std::to_string(k));
        s.pair_index.push_back(k / 2);
    }
    return s;
}

cluster::RunOptions runner(cluster::RunnerKind kind) {
    cluster::RunOptions o;
    o.runner = kind;
    o.jobs = 2;
    o.retries = 0;
    o.worker = {HC_HARRIS_COSIM, "shard", "run"};
    o.merger = {HC_HARRIS_COSIM, "shard", "merge"};
    o.slurm.poll_s = 0.5;
    return o;
}

/// The boundaries the chain check passed in merged eval data, set to 0 in `merged`.
int take_chain_checked(json& merged) {
    int n = 0;
    for (auto& q : merged.at("sequences")) {
        n += q.at("chain").at(2).get<int>();
        q.at("chain").at(2) = 0;
    }
    return n;
}

/// The job run sharded through `kind` and the same evaluation in one process (one shard
/// per sequence) give the same data, but for the boundaries the chain check passed: every
/// boundary within a sequence of a cycle run, none elsewhere.
void check_sharded_equals_single(const cluster::Manifest& sharded, const cluster::Manifest& single,
                                 cluster::RunnerKind kind, const std::string& name) {
    const fs::path dir = scratch(name);
    json merged = cluster::run_and_merge(tools::registry(), dir, sharded, runner(kind));
    json once = cluster::run_in_process(tools::registry(), single);
    if (sharded.job == "eval") {
        const bool cycle = sharded.common.at("source") == "cycle";
        CHECK(take_chain_checked(merged) ==
              (cycle ? static_cast<int>(sharded.shards.size() - merged.at("sequences").size()) : 0));
        CHECK(take_chain_checked(once) == 0);
    }
    CHECK(merged == once);
    CHECK(cluster::merged_path(dir).string().size() > 0);
    CHECK(fs::exists(cluster::merged_path(dir)));
}

}  // namespace

TEST_CASE("the cycle model's saved state restores every register and the run continues identically", "[cluster]") {
    const Geometry g{64, 36};
    const auto s = pattern_stream(64, 36, 3);
    const auto ptrs = frames::pointers(s.frames);
    HostDriver da(g, ptrs), db(g, ptrs);
    HarrisTop a(g, Formats{}), b(g, Formats{});
    BusEvent ev, evb;
    for (int w = 0; w < 5000 && da.next(ev); ++w) a.write(ev.data);
    const std::string image = a.save_state();
    b.restore_state(image);
    db.restore(da.state());
    CHECK(db.state() == da.state());
    CHECK(b.save_state() == image);
    CHECK(b.writes() == 5000);
    long compared = 0, differing = 0;
    while (da.next(ev)) {
        REQUIRE(db.next(evb));
        CHECK(evb.data == ev.data);
        a.write(ev.data);
        b.write(evb.data);
        differing += a.corner() != b.corner() || a.thr().value() != b.thr().value();
        if (++compared % 997 == 0) differing += a.save_state() != b.save_state();
    }
    CHECK_FALSE(db.next(evb));
    CHECK(compared > 5000);
    CHECK(differing == 0);
    CHECK(a.save_state() == b.save_state());

    HarrisTop other(Geometry{66, 36}, Formats{});
    CHECK_THROWS_AS(other.restore_state(image), std::invalid_argument);
    CHECK_THROWS_AS(b.restore_state(image.substr(0, image.size() - 1)), std::invalid_argument);
}

TEST_CASE("cycle runs started at checkpoints report exactly the serial run's frames", "[cluster]") {
    const auto s = pattern_stream(96, 40, 8);
    const Formats f{};
    const eval::CycleRun serial = eval::run_cycle(s, f, false);
    const eval::CycleCheckpoint c2 = eval::checkpoint_from_json(eval::to_json(eval::cycle_checkpoint(s, f, 0, 8, nullptr, 2)));
    // the second checkpoint from the first, over only the frames it needs (2..5)
    eval::Stream held;
    for (int k = 2; k <= 5; ++k) {
        held.frames.push_back(s.frames[k]);
        held.names.push_back(s.names[k]);
        held.pair_index.push_back(s.pair_index[k]);
    }
    const eval::CycleCheckpoint c5 = eval::cycle_checkpoint(held, f, 2, 8, &c2, 5);
    CHECK(c5.frame == 5);
    CHECK(c5.writes > c2.writes);
    std::vector<eval::CycleRun> parts;
    parts.push_back(eval::run_cycle(s, f, eval::CycleSpan{0, 0, 2, 8, nullptr, c2.writes}, false));
    parts.push_back(eval::run_cycle(held, f, eval::CycleSpan{2, 2, 5, 8, &c2, c5.writes}, false));
    parts.push_back(eval::run_cycle(s, f, eval::CycleSpan{0, 5, 8, 8, &c5, 0}, false));
    const int firsts[] = {0, 2, 5};
    long writes = 0, reads = 0, mixed = 0, publications = 0, frames_equal = 0;
    for (int p = 0; p < 3; ++p) {
        const auto& r = parts[static_cast<std::size_t>(p)];
        writes += r.writes;
        reads += r.reads;
        mixed += r.mixed_windows;
        publications += r.max_publications;
        for (std::size_t k = 0; k < r.masks.size(); ++k) {
            const std::size_t fr = static_cast<std::size_t>(firsts[p]) + k;
            // a frame's maximum: the part's own publication, else the previous part's
            // during this frame's preloaded columns
            const std::int64_t max = k == 0 && p > 0 && r.publications_in_frame[0] == 0 &&
                                             parts[static_cast<std::size_t>(p) - 1].next_publications > 0
                                         ? parts[static_cast<std::size_t>(p) - 1].next_max
                                         : r.max[k];
            frames_equal += r.masks[k] == serial.masks[fr] && r.thr_map[k] == serial.thr_map[fr] &&
                            r.thr[k] == serial.thr[fr] && max == serial.max[fr];
        }
    }
    CHECK(frames_equal == 8);
    CHECK(writes == serial.writes);
    CHECK(reads == serial.reads);
    CHECK(mixed == serial.mixed_windows);
    CHECK(publications == serial.max_publications);
    CHECK(serial.max_publications >= 4);   // maxima published in several frames
}

TEST_CASE("a checkpoint from a warm-up of six frames equals the one from the serial run", "[cluster]") {
    const auto s = pattern_stream(96, 40, 12);
    const Formats f{};
    const eval::CycleCheckpoint serial = eval::cycle_checkpoint(s, f, 0, 12, nullptr, 10);
    const eval::CheckpointBase base = eval::checkpoint_base(s, f, 12);
    CHECK(base.writes_per_frame > 0);
    eval::Stream held;   // frames 4..10 only
    for (int k = 4; k <= 10; ++k) {
        held.frames.push_back(s.frames[k]);
        held.names.push_back(s.names[k]);
        held.pair_index.push_back(s.pair_index[k]);
    }
    const eval::CycleCheckpoint warm = eval::warm_checkpoint(held, f, 4, 12, base, 10, 6);
    CHECK(warm.writes == serial.writes);
    CHECK(warm.driver == serial.driver);
    CHECK(warm.model == serial.model);
    CHECK(eval::to_json(warm) == eval::to_json(serial));
    // too short a warm-up to flush find-max's maximum is refused
    CHECK_THROWS_AS(eval::warm_checkpoint(held, f, 4, 12, base, 10, 1), InternalError);
}

TEST_CASE("every warm-up of three frames that is accepted gives the serial run's checkpoint", "[cluster]") {
    const auto s = pattern_stream(96, 40, 12);
    const Formats f{};
    const eval::CheckpointBase base = eval::checkpoint_base(s, f, 12);
    std::vector<int> accepted, refused;
    for (int to = 4; to < 12; ++to) {
        INFO("checkpoint at frame " << to);
        const eval::CycleCheckpoint serial = eval::cycle_checkpoint(s, f, 0, 12, nullptr, to);
        try {
            const eval::CycleCheckpoint warm = eval::warm_checkpoint(s, f, 0, 12, base, to, 3);
            CHECK(eval::to_json(warm) == eval::to_json(serial));
            accepted.push_back(to);
        } catch (const InternalError&) {
            refused.push_back(to);   // fewer than 3 publications: a longer warm-up is needed
        }
    }
    // this stream's period counter: 3 publications in 3 frames before frames 4..7 and 11 only
    CHECK(accepted == std::vector<int>{4, 5, 6, 7, 11});
    CHECK(refused == std::vector<int>{8, 9, 10});
}

TEST_CASE("the spec model's threshold of a frame depends only on the previous frame", "[cluster]") {
    const auto s = pattern_stream(96, 40, 6);
    const auto whole = eval::run_spec(s, spec::Options{}, 1);
    eval::Stream tail;   // frames 3.. with frame 2 before them for its maximum
    for (int k = 2; k < 6; ++k) {
        tail.frames.push_back(s.frames[k]);
        tail.names.push_back(s.names[k]);
        tail.pair_index.push_back(s.pair_index[k]);
    }
    const auto part = eval::run_spec(tail, spec::Options{}, 1);
    for (int k = 3; k < 6; ++k) {
        CHECK(part.masks[k - 2] == whole.masks[k]);
        CHECK(part.thr[k - 2] == whole.thr[k]);
    }
}

TEST_CASE("the spec model after a frame given for its maximum only equals the run through that frame, in every ablation variant", "[cluster]") {
    const auto s = pattern_stream(96, 40, 6);
    eval::Stream tail;   // frames 3..5, frame 2 given for its maximum only
    for (int k = 3; k < 6; ++k) {
        tail.frames.push_back(s.frames[k]);
        tail.names.push_back(s.names[k]);
        tail.pair_index.push_back(s.pair_index[k]);
    }
    for (const auto& v : eval::ablation_variants()) {
        INFO("variant " << v.name);
        const auto whole = eval::run_spec(s, v.opt, 1);
        const auto part = eval::run_spec(tail, v.opt, 1, &s.frames[2]);
        REQUIRE(part.masks.size() == 3);
        for (int k = 3; k < 6; ++k) {
            INFO("frame " << k);
            CHECK(part.masks[k - 3] == whole.masks[k]);
            CHECK(part.thr[k - 3] == whole.thr[k]);
            CHECK(part.max[k - 3] == whole.max[k]);
        }
    }
}

TEST_CASE("missing sequences are named", "[cluster]") {
    try {
        frames::check_kitti_sequences(standin(), {"02", "04", "03", "09"});
        FAIL("missing sequences were not reported");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("04, 09") != std::string::npos);
    }
}

TEST_CASE("spec and cycle evaluations sharded within sequences merge to the single-process data", "[cluster]") {
    eval::EvalJob j = standin_job({"02", "03"}, "spec", true);
    for (const char* source : {"spec", "cycle"}) {
        j.source = source;
        const auto [single, sharded] = single_and_sharded(j, 5);
        REQUIRE(single.shards.size() == 2);
        REQUIRE(sharded.shards.size() == 5);
        if (std::string(source) == "cycle") CHECK_FALSE(sharded.shards[1].at("start").is_null());
        check_sharded_equals_single(sharded, single, cluster::RunnerKind::local, std::string("local-") + source);
        const eval::Report r = eval::eval_report(cluster::run_in_process(tools::registry(), single));
        CHECK(r.frames.size() == 24);
        CHECK(r.sequences.size() == 2);
    }
}

TEST_CASE("a sharded cycle run checks its chain at every boundary and refuses a checkpoint from too short a warm-up", "[cluster]") {
    eval::EvalJob j = standin_job({"02"}, "cycle", false);
    j.shards = 3;
    cluster::Manifest m = eval::eval_manifest(j);
    REQUIRE(m.shards.size() == 3);
    // the good chain: two boundaries checked, and the report says so
    {
        const eval::Report r = eval::eval_report(cluster::run_in_process(tools::registry(), m));
        CHECK(std::count(r.notes.begin(), r.notes.end(),
                         "Sharded cycle run: chain checked at 2 boundaries (at each, the cycle model's registers, the "
                         "host driver's position and the recent writes where a part stopped equal the next part's "
                         "starting checkpoint).") == 1);
    }
    // the last part from a one-frame warm-up (its find-max maximum not flushed)
    const int p0 = m.shards[2].at("pairs").at(0), p1 = m.shards[2].at("pairs").at(1);
    const int to_pair = m.shards[2].at("part").at(0), to = 2 * (to_pair - p0);
    const eval::Stream s = frames::load_kitti_stream(standin(), "02", {p0, p1}, "the stand-in", 1);
    const eval::CheckpointBase base = eval::checkpoint_base(s, Formats{}, 2 * (p1 - p0));
    const eval::CycleCheckpoint bad = eval::warm_checkpoint(s, Formats{}, 0, 2 * (p1 - p0), base, to, 1, 0);
    REQUIRE(eval::to_json(bad) != m.shards[2].at("start"));   // the short warm-up does give another state
    m.shards[2]["start"] = eval::to_json(bad);
    try {
        cluster::run_in_process(tools::registry(), m);
        FAIL("the merge accepted a part started from a wrong checkpoint");
    } catch (const SimulatorError& e) {
        const std::string what = e.what();
        INFO(what);
        CHECK(what.find("chain check failed at the boundary before frame " + std::to_string(to) + " (02/L" +
                        fmt::format("{:06}", to_pair) + ", stereo pair " + std::to_string(to_pair) + ") of sequence 02") !=
              std::string::npos);
        CHECK(what.find(eval::chain_digest(bad)) != std::string::npos);
    }
}

TEST_CASE("rtl evaluations and verilate runs sharded by sequence merge to the single-process data", "[cluster][rtl]") {
    const cluster::Manifest m = eval::eval_manifest(standin_job({"02", "03"}, "rtl", false));
    REQUIRE(m.shards.size() == 2);
    vl::prepare_rtl(m);
    check_sharded_equals_single(m, m, cluster::RunnerKind::local, "local-rtl");
    vl::VerilateJob v;
    v.kitti = standin();
    v.sequences = {"02", "03"};
    const cluster::Manifest vm = vl::verilate_manifest(v);
    vl::prepare_rtl(vm);
    const json once = cluster::run_in_process(tools::registry(), vm);
    CHECK(once.at("status") == "pass");
    CHECK(once.at("totals").at("frames") == 24);
    check_sharded_equals_single(vm, vm, cluster::RunnerKind::local, "local-verilate");
}

TEST_CASE("a Slurm array of cycle shards within KITTI 01 merges to the single-process data", "[slurm][kitti]") {
    eval::EvalJob j;
    j.kitti = g_kitti;
    j.sequences = {"01"};
    j.pairs = {0, 8};
    j.source = "cycle";
    j.ablation = false;
    j.threads = 1;
    const auto [single, sharded] = single_and_sharded(j, 4);
    REQUIRE(sharded.shards.size() == 4);
    check_sharded_equals_single(sharded, single, cluster::RunnerKind::slurm, "slurm-cycle");
}

TEST_CASE("a Slurm array of rtl shards, one per sequence, merges to the single-process data", "[slurm]") {
    const cluster::Manifest m = eval::eval_manifest(standin_job({"02", "03"}, "rtl", false));
    vl::prepare_rtl(m);
    check_sharded_equals_single(m, m, cluster::RunnerKind::slurm, "slurm-rtl");
}

int main(int argc, char** argv) {
    if (argc == 3 && std::strcmp(argv[1], "--make-standin") == 0) {
        make_standin(argv[2]);
        return 0;
    }
    if (argc == 6 && std::strcmp(argv[1], "--make-standin") == 0) {   // DIR SEQ WxH PAIRS
        const auto [w, h] = util::parse_size(argv[4], "size");
        test::write_standin_sequence(argv[2], argv[3], w, h, std::stoi(argv[5]), Pattern::blocks, 3);
        return 0;
    }
    bool kitti = false;
    for (int k = 1; k < argc; ++k) kitti |= std::strstr(argv[k], "kitti") != nullptr;
    const auto d = frames::data_dir("");
    if (d && fs::is_directory(*d / "kitti/sequences/01/image_0")) g_kitti = *d / "kitti";
    if (kitti && g_kitti.empty()) {
        std::printf("SKIPPED: no KITTI sequence 01 (set HARRIS_COSIM_DATA to a directory holding "
                    "kitti/sequences/01; see the data README.md (../shared/data beside the repository))\n");
        return 77;
    }
    const int rc = hc::test::run_catch(argc, argv);
    std::error_code ec;
    fs::remove_all(fs::temp_directory_path() / ("hc-eval-jobs-" + std::to_string(::getpid())), ec);
    return rc;
}
