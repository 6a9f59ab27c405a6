// runner.cpp: see runner.hpp.
#include "io/cluster/runner.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace hc::cluster {

std::string sharding_flags_named() {
    std::string s;
    for (const char* f : kShardingFlags) s += (s.empty() ? "" : ", ") + std::string(f);
    return "the sharding flags (" + s + ")";
}

fs::path folder_of(const std::string& file) { return file.empty() ? fs::path() : fs::path(file).parent_path(); }

fs::path resolve_program(const char* argv0) {
    fs::path p = argv0 ? argv0 : "";
    std::error_code ec;
    if (p.has_parent_path()) {
        fs::path c = fs::canonical(p, ec);
        return ec ? fs::absolute(p) : c;
    }
    if (const char* path = std::getenv("PATH")) {
        std::stringstream ss(path);
        std::string d;
        while (std::getline(ss, d, ':')) {
            fs::path c = fs::path(d.empty() ? "." : d) / p;
            if (fs::exists(c)) return fs::canonical(c);
        }
    }
    return p;
}

std::string status_text(const fs::path& dir) {
    const Manifest m = read_manifest(dir);
    const auto missing = missing_shards(dir, m);
    std::string s = dir.string() + ": job " + m.job + ", " + std::to_string(m.shards.size() - missing.size()) + " of " +
                    std::to_string(m.shards.size()) + " shards done\n";
    for (std::size_t i : missing) {
        const ResultCheck c = check_result(dir, m, i);
        if (c.state == ResultState::damaged)
            s += "  damaged " + std::to_string(i) + ": " + result_path(dir, i).string() + " " + c.why +
                 " (--resume sets it aside and runs the shard again)\n";
        else
            s += "  missing " + std::to_string(i) + " (log " + log_path(dir, i).string() + ")\n";
    }
    return s;
}

fs::path JobRunner::run_dir(const fs::path& out) const {
    if (!s_.run_dir.empty()) return s_.run_dir;
    return (out.empty() ? fs::path(".") : out) / "run";
}

RunOptions JobRunner::options(const fs::path& dir, bool fork) const {
    if (!s_.resume && fs::exists(dir / "shards") && !fs::is_empty(dir / "shards"))
        throw InputError("run directory " + dir.string() +
                         " already holds shard results: add --resume to continue that run, or choose another --run-dir");
    RunOptions o;
    o.runner = s_.runner == "slurm" ? RunnerKind::slurm : RunnerKind::local;
    o.jobs = s_.jobs;
    o.retries = s_.retries;
    o.worker = {program_.string(), "shard", "run"};
    o.merger = {program_.string(), "shard", "merge"};
    o.slurm.partition = s_.partition;
    o.slurm.account = s_.account;
    o.slurm.time = s_.time;
    o.slurm.mem = s_.mem;
    o.slurm.wait = !s_.no_wait;
    o.progress = [](const Progress& p) {
        std::fprintf(stderr, "[shards] %zu/%zu done%s, %.0f s elapsed, ETA %.0f s\n", p.done, p.total,
                     p.failed ? (", " + std::to_string(p.failed) + " failed").c_str() : "", p.elapsed_s, p.eta_s);
    };
    o.notice = [](const std::string& line) { std::fprintf(stderr, "[shards] %s\n", line.c_str()); };
    if (fork) o.fork_worker = [this](const fs::path& d, std::size_t i) { run_worker(d, i); };
    return o;
}

std::optional<json> JobRunner::run(const Manifest& m, const fs::path& out, bool fork) const {
    if (!s_.sharded) return run_in_process(*reg_, m);
    return run_in(run_dir(out), m, fork);
}

std::optional<json> JobRunner::run_in(const fs::path& dir, const Manifest& m, bool fork) const {
    const RunOptions o = options(dir, fork);
    if (o.runner == RunnerKind::slurm && !o.slurm.wait) {
        reg_->at(m.job);   // an unknown kind is bad input before anything is written
        prepare_run(dir, m);
        const RunSummary s = cluster::run(dir, o);
        if (s.ran == 0) return merge_run(*reg_, dir);   // every shard already has its result
        std::printf("harris-cosim: submitted %zu shard(s) of %s as Slurm array job %s, merge job %s.\n"
                    "`harris-cosim shard status %s` shows what is missing; when both jobs are done, the same\n"
                    "command with --resume renders the report from the merged results without running anything.\n",
                    s.ran, dir.c_str(), s.slurm_array_job.c_str(),
                    s.slurm_merge_job.empty() ? "(none)" : s.slurm_merge_job.c_str(), dir.c_str());
        return std::nullopt;
    }
    return run_and_merge(*reg_, dir, m, o);
}

void JobRunner::run_worker(const fs::path& dir, std::size_t index) const {
    run_shard(*reg_, dir, index, {{"harris-cosim", version_}});
}

}  // namespace hc::cluster
