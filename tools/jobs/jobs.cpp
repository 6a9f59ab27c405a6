// jobs.cpp: the registry of job kinds and the run-then-merge sequence every sharded command uses.
#include "tools/jobs/jobs.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "io/util/util.hpp"

namespace hc::jobs {

const cluster::JobRegistry& registry() {
    static const cluster::JobRegistry reg = [] {
        cluster::JobRegistry r;
        add_eval_job(r);
        add_verilate_job(r);
        r.add(detail::sweep_job());
        r.add(detail::sweep_check_job());
        r.add(detail::mutate_job());
        r.add(detail::landmarks_job());
        r.add(detail::slam_job());
        add_mutants_job(r);
        return r;
    }();
    return reg;
}

namespace detail {

json doubles(const std::vector<double>& v) {
    json a = json::array();
    for (double x : v) a.push_back(std::isnan(x) ? json(nullptr) : json(x));
    return a;
}

std::vector<double> doubles(const json& j) {
    std::vector<double> v;
    for (const auto& x : j) v.push_back(x.is_null() ? std::numeric_limits<double>::quiet_NaN() : x.get<double>());
    return v;
}

std::vector<std::pair<long, long>> groups(long n, int k) {
    if (n <= 0) return {};
    return cluster::split_range(0, n, k <= 0 || k > n ? static_cast<int>(n) : k);
}

}  // namespace detail

fs::path merged_path(const fs::path& dir) { return dir / "merged.json"; }

json merge_run(const fs::path& dir) {
    json merged = cluster::merge(registry(), dir);
    util::write_file_atomic(merged_path(dir), merged.dump(1) + "\n");
    return merged;
}

json run_and_merge(const fs::path& dir, const cluster::Manifest& m, const cluster::RunOptions& o) {
    registry().at(m.job);   // an unknown kind is bad input before anything is written
    cluster::prepare_run(dir, m);
    const cluster::RunSummary s = cluster::run(dir, o);
    if (!s.failed.empty()) {
        std::string which;
        for (std::size_t i : s.failed) which += (which.empty() ? "" : ", ") + std::to_string(i);
        throw cluster::ClusterRunError(std::to_string(s.failed.size()) + " of " + std::to_string(s.shards) +
                                       " shard(s) of " + dir.string() + " have no result (" + which +
                                       "; logs in " + (dir / "logs").string() +
                                       "); the same command resumes and runs only those");
    }
    return merge_run(dir);
}

}  // namespace hc::jobs
