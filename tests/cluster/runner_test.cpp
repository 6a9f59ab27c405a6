// runner_test: the JobRunner every command hands its manifests to (io/cluster/runner.hpp):
// one process when no sharding flag was given, shards in the default run directory
// otherwise (started workers or forked ones), an earlier run's results never silently
// reused, and the status text of a run directory.
#include <catch2/catch.hpp>

#include "io/cluster/runner.hpp"
#include "tests/cluster/squares_job.hpp"

using namespace hc::cluster;
using hc::cluster::test::squares_manifest;
using hc::cluster::test::squares_registry;

namespace {

fs::path runner_scratch(const std::string& name) { return hc::cluster::test::scratch("runner-" + name); }

JobRunner runner(const JobRegistry& reg, bool sharded, bool resume = false) {
    RunnerSettings s;
    s.sharded = sharded;
    s.resume = resume;
    s.jobs = 2;
    return JobRunner(reg, s, HC_TEST_WORKER, "test");
}

}  // namespace

TEST_CASE("without a sharding flag the runner computes every shard in this process and writes no run directory",
          "[cluster]") {
    const JobRegistry reg = squares_registry();
    const fs::path out = runner_scratch("single");
    const auto got = runner(reg, false).run(squares_manifest(100, 4), out);
    REQUIRE(got);
    CHECK(got->at("sum").get<long>() == 328350);   // sum of i^2, i < 100
    CHECK(*got == run_in_process(reg, squares_manifest(100, 4)));
    CHECK_FALSE(fs::exists(out / "run"));
}

TEST_CASE("a sharded run lands in <out>/run, started or forked, and equals the single-process data", "[cluster]") {
    const JobRegistry reg = squares_registry();
    const Manifest m = squares_manifest(50, 5);
    for (const bool fork : {false, true}) {
        const fs::path out = runner_scratch(fork ? "forked" : "started");
        const JobRunner r = runner(reg, true);
        CHECK(r.run_dir(out) == out / "run");
        const auto got = r.run(m, out, fork);
        REQUIRE(got);
        CHECK(*got == run_in_process(reg, m));
        CHECK(fs::exists(merged_path(out / "run")));
        CHECK(status_text(out / "run") == (out / "run").string() + ": job squares, 5 of 5 shards done\n");
    }
}

TEST_CASE("a run directory holding results is refused without --resume and merged with it", "[cluster]") {
    const JobRegistry reg = squares_registry();
    const Manifest m = squares_manifest(30, 3);
    const fs::path out = runner_scratch("resume");
    REQUIRE(runner(reg, true).run(m, out));
    CHECK_THROWS_WITH(runner(reg, true).run(m, out),
                      Catch::Contains((out / "run").string()) && Catch::Contains("add --resume"));
    const auto again = runner(reg, true, /*resume=*/true).run(m, out);
    REQUIRE(again);
    CHECK(*again == run_in_process(reg, m));
}

TEST_CASE("the run directory is --run-dir when given, else beside the output", "[cluster]") {
    const JobRegistry reg = squares_registry();
    RunnerSettings s;
    s.run_dir = "elsewhere";
    CHECK(JobRunner(reg, s, "x", "v").run_dir("out") == "elsewhere");
    CHECK(JobRunner(reg, {}, "x", "v").run_dir("") == fs::path(".") / "run");
    CHECK(folder_of("") == fs::path());
    CHECK(folder_of("report.md") == fs::path());
    CHECK(folder_of("docs/report.md") == fs::path("docs"));
    CHECK(sharding_flags_named() == "the sharding flags (--runner, --shards, --run-dir, --resume)");
}
