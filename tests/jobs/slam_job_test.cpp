// slam_job_test: Monte-Carlo seeds run in shards by `harris-cosim shard run` and folded by
// slam::slam_result give slam::monte_carlo's statistics bit for bit.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstring>
#include <filesystem>

#include "mapping/slam/slam_job.hpp"
#include "tools/registry.hpp"

using namespace hc;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (!same_bits(a[i], b[i])) return false;
    return true;
}

template <class M>
bool same_bits(const std::vector<M>& a, const std::vector<M>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(a[i].data(), b[i].data(), sizeof(double) * a[i].size()) != 0) return false;
    return true;
}

}  // namespace

TEST_CASE("seven seeds in three shards fold to the single-process Monte-Carlo statistics bit for bit", "[cluster]") {
    slam::SimConfig c;
    c.steps = 60;
    slam::SlamJob p;
    p.config = c;
    p.runs = 7;
    p.first_seed = 3;
    p.shards = 3;
    const cluster::Manifest m = slam::slam_manifest(p);
    REQUIRE(m.shards.size() == 3);
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("hc-slam-job-test-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    cluster::RunOptions o;
    o.jobs = 2;
    o.worker = {HC_CLI, "shard", "run"};
    const nlohmann::json merged = cluster::run_and_merge(tools::registry(), dir, m, o);
    CHECK(merged == cluster::run_in_process(tools::registry(), m));

    const slam::MonteCarlo a = slam::slam_result(m, merged);
    const slam::MonteCarlo b = slam::monte_carlo(c, 7, 3);
    CHECK(a.runs == 7);
    CHECK(a.pose_nees.size() == 61);
    using MC = slam::MonteCarlo;
    const std::pair<const char*, std::vector<double> MC::*> per_step[] = {
        {"pose_nees", &MC::pose_nees},         {"map_nees_per_dof", &MC::map_nees_per_dof}, {"map_lo", &MC::map_lo},
        {"map_hi", &MC::map_hi},               {"position_rmse", &MC::position_rmse},       {"heading_rmse", &MC::heading_rmse},
        {"map_rmse", &MC::map_rmse}};
    for (const auto& [name, field] : per_step) {
        INFO(name);
        CHECK(same_bits(a.*field, b.*field));
    }
    const std::pair<const char*, double MC::*> scalars[] = {
        {"pose_lo", &MC::pose_lo},         {"pose_hi", &MC::pose_hi},
        {"pose_inside", &MC::pose_inside}, {"map_inside", &MC::map_inside},
        {"pose_nees_average", &MC::pose_nees_average}, {"map_nees_per_dof_average", &MC::map_nees_per_dof_average}};
    for (const auto& [name, field] : scalars) {
        INFO(name);
        CHECK(same_bits(a.*field, b.*field));
    }
    // the first seed's run, which the report draws
    CHECK(same_bits(a.first.truth, b.first.truth));
    CHECK(same_bits(a.first.estimate, b.first.estimate));
    CHECK(same_bits(a.first.pose_cov, b.first.pose_cov));
    CHECK(same_bits(a.first.pose_nees, b.first.pose_nees));
    CHECK(a.first.map_dof == b.first.map_dof);
    CHECK(same_bits(a.first.world.landmarks, b.first.world.landmarks));
    CHECK(same_bits(a.first.final_map, b.first.final_map));
    CHECK(same_bits(a.first.final_map_cov, b.first.final_map_cov));
    std::filesystem::remove_all(dir);
}

TEST_CASE("a slam manifest refuses a bad run count with the input named", "[cluster]") {
    slam::SlamJob p;
    p.runs = 0;
    CHECK_THROWS_WITH(slam::slam_manifest(p), Catch::Contains("--runs must be at least 1"));
}
