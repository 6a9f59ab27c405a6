// cluster_test: shards, result files, the local runner, resume after a failed and a killed
// shard, and (with a running Slurm cluster, tag [slurm]) the Slurm runner. Every run's
// merged result must equal the single-process result exactly.
#include <catch2/catch.hpp>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <thread>

#include "io/cluster/cluster.hpp"
#include "tests/cluster/squares_job.hpp"

extern char** environ;

using namespace hc::cluster;
using hc::cluster::test::squares_manifest;
using hc::cluster::test::squares_registry;

using hc::cluster::test::scratch;

namespace {

RunOptions local_options(int jobs) {
    RunOptions o;
    o.jobs = jobs;
    o.worker = {HC_TEST_WORKER};
    return o;
}

long sum_of_squares_below(long n) { return (n - 1) * n * (2 * n - 1) / 6; }

}  // namespace

TEST_CASE("a range splits into contiguous parts whose sizes differ by at most one", "[cluster]") {
    using V = std::vector<std::pair<long, long>>;
    CHECK(split_range(0, 10, 4) == V{{0, 3}, {3, 6}, {6, 8}, {8, 10}});
    CHECK(split_range(5, 7, 4) == V{{5, 6}, {6, 7}});
    CHECK(split_range(3, 3, 2) == V{{3, 3}});
    CHECK_THROWS_AS(split_range(4, 3, 2), hc::InputError);
    CHECK_THROWS_AS(split_range(0, 3, 0), hc::InputError);
}

TEST_CASE("a run directory refuses the manifest of another run", "[cluster]") {
    const fs::path d = scratch("foreign");
    prepare_run(d, squares_manifest(20, 2));
    REQUIRE_NOTHROW(prepare_run(d, squares_manifest(20, 2)));
    CHECK_THROWS_AS(prepare_run(d, squares_manifest(20, 3)), hc::InputError);
    CHECK(read_manifest(d).hash() == squares_manifest(20, 2).hash());
}

TEST_CASE("the local runner's merged result equals the single-process result", "[cluster]") {
    const fs::path d = scratch("local");
    const Manifest m = squares_manifest(100, 7);
    prepare_run(d, m);
    std::size_t last_done = 0, calls = 0;
    RunOptions o = local_options(2);
    o.progress = [&](const Progress& p) {
        ++calls;
        CHECK(p.total == 7);
        CHECK(p.done >= last_done);
        last_done = p.done;
    };
    const RunSummary s = run(d, o);
    CHECK(s.ran == 7);
    CHECK(s.failed.empty());
    CHECK(calls == 7);
    CHECK(last_done == 7);
    const json merged = merge(squares_registry(), d);
    CHECK(merged == run_in_process(squares_registry(), m));
    CHECK(merged.at("sum").get<long>() == sum_of_squares_below(100));
    CHECK(merged.at("items").size() == 100);
}

TEST_CASE("a failed shard stays missing, the merge names it, and a resume runs only it", "[cluster]") {
    const fs::path d = scratch("failed");
    const Manifest m = squares_manifest(40, 4);
    prepare_run(d, m);
    ::setenv("HC_TEST_FAIL_INDEX", "2", 1);
    RunOptions o = local_options(2);
    o.retries = 1;
    const RunSummary s1 = run(d, o);
    ::unsetenv("HC_TEST_FAIL_INDEX");
    CHECK(s1.ran == 5);   // four shards, shard 2 twice
    CHECK(s1.failed == std::vector<std::size_t>{2});
    CHECK(missing_shards(d, m) == std::vector<std::size_t>{2});
    CHECK_THROWS_WITH(merge(squares_registry(), d), Catch::Contains("shards without a result: 2"));
    const RunSummary s2 = run(d, o);
    CHECK(s2.ran == 1);
    CHECK(s2.skipped == 3);
    CHECK(s2.failed.empty());
    CHECK(merge(squares_registry(), d) == run_in_process(squares_registry(), m));
}

TEST_CASE("a shard killed mid-run leaves no result, and a resume completes the run exactly once",
          "[cluster]") {
    const fs::path d = scratch("killed");
    const Manifest m = squares_manifest(30, 3);
    prepare_run(d, m);
    // Shard 1's worker sleeps before computing: it is killed while it runs.
    std::vector<std::string> a = {HC_TEST_WORKER, d.string(), "1"};
    std::vector<char*> argv;
    for (auto& s : a) argv.push_back(s.data());
    argv.push_back(nullptr);
    ::setenv("HC_TEST_SLEEP_INDEX", "1", 1);
    pid_t pid = 0;
    REQUIRE(::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) == 0);
    ::unsetenv("HC_TEST_SLEEP_INDEX");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    REQUIRE(::kill(pid, SIGKILL) == 0);
    int st = 0;
    ::waitpid(pid, &st, 0);
    CHECK(WIFSIGNALED(st));
    CHECK(missing_shards(d, m) == std::vector<std::size_t>{0, 1, 2});
    const RunSummary s = run(d, local_options(2));
    CHECK(s.ran == 3);
    CHECK(s.failed.empty());
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(d / "shards")) {
        ++files;
        CHECK(e.path().extension() == ".json");
    }
    CHECK(files == 3);
    const json merged = merge(squares_registry(), d);
    CHECK(merged == run_in_process(squares_registry(), m));
    CHECK(merged.at("items").size() == 30);
}

TEST_CASE("forked workers write what started ones write, print into the shard's log, and a worker that throws leaves its shard missing",
          "[cluster]") {
    const fs::path d = scratch("forked");
    const Manifest m = squares_manifest(60, 5);
    prepare_run(d, m);
    RunOptions o = local_options(2);
    o.worker = {"/nonexistent/cluster-worker"};   // never started: each shard runs in a fork
    o.retries = 0;
    o.fork_worker = [](const fs::path& dir, std::size_t index) {
        std::printf("forked worker of shard %zu\n", index);
        if (index == 3) throw std::runtime_error("no result for this one");
        run_shard(squares_registry(), dir, index, {{"cluster_tests", "1"}});
    };
    const RunSummary s = run(d, o);
    CHECK(s.ran == 5);
    CHECK(s.failed == std::vector<std::size_t>{3});
    const auto log = [&](std::size_t i) {
        std::ifstream f(log_path(d, i));
        return std::string(std::istreambuf_iterator<char>(f), {});
    };
    CHECK(log(0) == "forked worker of shard 0\n");
    CHECK(log(3) == "forked worker of shard 3\nshard 3: no result for this one\n");
    o.fork_worker = [](const fs::path& dir, std::size_t index) {
        run_shard(squares_registry(), dir, index, {{"cluster_tests", "1"}});
    };
    const RunSummary resumed = run(d, o);
    CHECK(resumed.ran == 1);
    CHECK(resumed.skipped == 4);
    CHECK(merge(squares_registry(), d) == run_in_process(squares_registry(), m));
}

TEST_CASE("a result file of another run is refused, not merged", "[cluster]") {
    const fs::path a = scratch("run-a"), b = scratch("run-b");
    const Manifest ma = squares_manifest(10, 2), mb = squares_manifest(12, 2);
    prepare_run(a, ma);
    prepare_run(b, mb);
    REQUIRE(run(a, local_options(1)).failed.empty());
    fs::copy_file(result_path(a, 0), result_path(b, 0));
    CHECK_THROWS_WITH(read_result(b, mb, 0), Catch::Contains("belongs to another run"));
}

namespace {

std::string file_text(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

void put_text(const fs::path& p, const std::string& s) {
    std::ofstream f(p, std::ios::binary | std::ios::trunc);
    f << s;
}

// A finished run of 4 shards whose result `index` is then damaged by `damage` (the file's
// bytes in, the damaged bytes out); returns the damaged bytes.
std::string run_then_damage(const fs::path& d, const Manifest& m, std::size_t index,
                            const std::function<std::string(const std::string&)>& damage) {
    prepare_run(d, m);
    REQUIRE(run(d, local_options(2)).failed.empty());
    const std::string damaged = damage(file_text(result_path(d, index)));
    put_text(result_path(d, index), damaged);
    return damaged;
}

// The damaged result of shard `index` is named as such, set aside by the next run (kept
// under its new name with its bytes, named in the shard's log and through `notice`), its
// shard alone runs again, and the merge equals the single-process result.
void check_recovered(const fs::path& d, const Manifest& m, std::size_t index, const std::string& damaged,
                     const std::string& why) {
    CHECK(check_result(d, m, index).state == ResultState::damaged);
    CHECK_THAT(check_result(d, m, index).why, Catch::Contains(why));
    CHECK(missing_shards(d, m) == std::vector<std::size_t>{index});
    CHECK_THROWS_WITH(read_result(d, m, index), Catch::Contains("is damaged") && Catch::Contains("--resume"));
    CHECK_THROWS_WITH(merge(squares_registry(), d), Catch::Contains("is damaged"));
    std::vector<std::string> notices;
    RunOptions o = local_options(2);
    o.notice = [&](const std::string& s) { notices.push_back(s); };
    const RunSummary s = run(d, o);
    CHECK(s.ran == 1);
    CHECK(s.skipped == m.shards.size() - 1);
    CHECK(s.failed.empty());
    const fs::path kept = result_path(d, index).string() + ".damaged-1";
    REQUIRE(s.set_aside.size() == 1);
    CHECK(s.set_aside[0].index == index);
    CHECK(s.set_aside[0].kept == kept);
    REQUIRE(fs::exists(kept));
    CHECK(file_text(kept) == damaged);
    REQUIRE(notices.size() == 1);
    CHECK_THAT(notices[0], Catch::Contains(kept.string()) && Catch::Contains(why));
    CHECK_THAT(file_text(log_path(d, index)), Catch::Contains(kept.string()));
    CHECK(check_result(d, m, index).state == ResultState::valid);
    CHECK(merge(squares_registry(), d) == run_in_process(squares_registry(), m));
}

}  // namespace

TEST_CASE("a truncated result is set aside and its shard runs again", "[cluster]") {
    const fs::path d = scratch("truncated");
    const Manifest m = squares_manifest(40, 4);
    const std::string damaged =
        run_then_damage(d, m, 3, [](const std::string& s) { return s.substr(0, s.size() / 2); });
    check_recovered(d, m, 3, damaged, "does not parse");
    // a second damage of the same shard is kept beside the first
    put_text(result_path(d, 3), "");
    RunOptions o = local_options(1);
    const RunSummary s = run(d, o);
    REQUIRE(s.set_aside.size() == 1);
    CHECK(s.set_aside[0].kept == result_path(d, 3).string() + ".damaged-2");
    CHECK(fs::exists(result_path(d, 3).string() + ".damaged-1"));
    CHECK(merge(squares_registry(), d) == run_in_process(squares_registry(), m));
}

TEST_CASE("a result whose content no longer matches its digest is set aside and its shard runs again", "[cluster]") {
    const fs::path d = scratch("digest");
    const Manifest m = squares_manifest(40, 4);
    // shard 1 holds 10..19: its sum 2185 becomes 2186, the digest stays
    const std::string damaged = run_then_damage(d, m, 1, [](std::string s) {
        const auto at = s.find("\"sum\": 2185");
        REQUIRE(at != std::string::npos);
        s.replace(at, 11, "\"sum\": 2186");
        return s;
    });
    REQUIRE(json::parse(damaged).at("data").at("sum") == 2186);
    check_recovered(d, m, 1, damaged, "does not match its digest");
}

TEST_CASE("a result written again with other whitespace is intact: the digest is of its content", "[cluster]") {
    const fs::path d = scratch("reindented");
    const Manifest m = squares_manifest(20, 2);
    const std::string before = run_then_damage(d, m, 1, [](const std::string& s) { return json::parse(s).dump(4); });
    CHECK(check_result(d, m, 1).state == ResultState::valid);
    const RunSummary s = run(d, local_options(1));
    CHECK(s.ran == 0);
    CHECK(s.set_aside.empty());
    CHECK(file_text(result_path(d, 1)) == before);
    CHECK(merge(squares_registry(), d) == run_in_process(squares_registry(), m));
}

TEST_CASE("a result without a digest is damaged, an intact result of another run still stops the run", "[cluster]") {
    const fs::path d = scratch("no-digest");
    const Manifest m = squares_manifest(20, 2);
    const std::string damaged = run_then_damage(d, m, 0, [](const std::string& s) {
        json j = json::parse(s);
        j.erase("digest");
        return j.dump(1);
    });
    check_recovered(d, m, 0, damaged, "carries no digest");
    const fs::path other = scratch("no-digest-other");
    const Manifest mo = squares_manifest(22, 2);
    prepare_run(other, mo);
    fs::copy_file(result_path(d, 1), result_path(other, 1));
    CHECK_THROWS_WITH(run(other, local_options(1)), Catch::Contains("belongs to another run"));
    CHECK(fs::exists(result_path(other, 1)));
}

TEST_CASE("the Slurm runner's merged result equals the single-process result", "[slurm]") {
    const char* conf = std::getenv("SLURM_CONF");
    if (!conf || !fs::exists(conf)) {
        WARN("no Slurm cluster (SLURM_CONF unset): skipped");
        return;
    }
    const fs::path d = scratch("slurm");
    const Manifest m = squares_manifest(50, 4);
    prepare_run(d, m);
    RunOptions o = local_options(1);
    o.runner = RunnerKind::slurm;
    o.slurm.poll_s = 0.5;
    const RunSummary s = run(d, o);
    CHECK(!s.slurm_array_job.empty());
    CHECK(s.failed.empty());
    CHECK(merge(squares_registry(), d) == run_in_process(squares_registry(), m));
}
