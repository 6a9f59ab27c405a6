// runner_flags.cpp: shared sharding flags, the worker's own path, progress lines.
#include "tools/runner_flags.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "tools/registry.hpp"
#include "io/util/errors.hpp"

namespace hc::tools {

namespace fs = std::filesystem;

void add_runner_flags(CLI::App* cmd, RunnerFlags& f) {
    const std::string g = "Sharding";
    cmd->add_option("--runner", f.runner, "where shards run: local (a pool of processes) or slurm (a job array)")
        ->check(CLI::IsMember({"local", "slurm"}))->capture_default_str()->group(g);
    cmd->add_option("--jobs", f.jobs, "local runner: shards at once")->check(CLI::Range(1, 1024))->capture_default_str()->group(g);
    cmd->add_option("--shards", f.shards, "number of shards (0: the command's default)")->check(CLI::Range(0, 100000))->group(g);
    cmd->add_option("--retries", f.retries, "local runner: extra attempts of a failed shard")->check(CLI::Range(0, 100))->capture_default_str()->group(g);
    cmd->add_option("--run-dir", f.run_dir, "directory of the run's manifest, shard results and logs (shared by all nodes for slurm)")->group(g);
    cmd->add_flag("--resume", f.resume, "continue the run in --run-dir: run only the shards without a result")->group(g);
    cmd->add_option("--partition", f.partition, "slurm: partition")->group(g);
    cmd->add_option("--account", f.account, "slurm: account")->group(g);
    cmd->add_option("--time", f.time, "slurm: time limit per shard (sbatch --time)")->group(g);
    cmd->add_option("--mem", f.mem, "slurm: memory per shard (sbatch --mem)")->group(g);
    cmd->add_flag("--no-wait", f.no_wait, "slurm: submit the array and the merge job and return")->group(g);
}

std::string sharding_flags_named() {
    std::string s;
    for (const char* f : kShardingFlags) s += (s.empty() ? "" : ", ") + std::string(f);
    return "the sharding flags (" + s + ")";
}

bool sharded(const CLI::App* cmd, bool single_jobs) {
    bool any = false;
    for (const char* f : kShardingFlags) any = any || cmd->count(f) > 0;
    if (!any && !single_jobs && cmd->count("--jobs") > 0)
        throw InputError("--jobs counts the shards run at once: give one of " + sharding_flags_named() + " to run " +
                         cmd->get_name() + " in shards");
    return any;
}

fs::path run_dir(const RunnerFlags& f, const fs::path& out) {
    if (!f.run_dir.empty()) return f.run_dir;
    return (out.empty() ? fs::path(".") : out) / "run";
}

fs::path folder_of(const std::string& file) { return file.empty() ? fs::path() : fs::path(file).parent_path(); }

namespace {
fs::path& program() {
    static fs::path p;
    return p;
}
}  // namespace

void set_program_path(const char* argv0) {
    fs::path p = argv0 ? argv0 : "";
    if (p.has_parent_path()) {
        std::error_code ec;
        fs::path c = fs::canonical(p, ec);
        program() = ec ? fs::absolute(p) : c;
        return;
    }
    if (const char* path = std::getenv("PATH")) {
        std::stringstream ss(path);
        std::string d;
        while (std::getline(ss, d, ':')) {
            fs::path c = fs::path(d.empty() ? "." : d) / p;
            if (fs::exists(c)) {
                program() = fs::canonical(c);
                return;
            }
        }
    }
    program() = p;
}

const fs::path& program_path() { return program(); }

cluster::RunOptions run_options(const RunnerFlags& f, const fs::path& dir) {
    if (!f.resume && fs::exists(dir / "shards") && !fs::is_empty(dir / "shards"))
        throw InputError("run directory " + dir.string() +
                         " already holds shard results: add --resume to continue that run, or choose another --run-dir");
    cluster::RunOptions o;
    o.runner = f.runner == "slurm" ? cluster::RunnerKind::slurm : cluster::RunnerKind::local;
    o.jobs = f.jobs;
    o.retries = f.retries;
    o.worker = {program_path().string(), "shard", "run"};
    o.merger = {program_path().string(), "shard", "merge"};
    o.slurm.partition = f.partition;
    o.slurm.account = f.account;
    o.slurm.time = f.time;
    o.slurm.mem = f.mem;
    o.slurm.wait = !f.no_wait;
    o.progress = [](const cluster::Progress& p) {
        std::fprintf(stderr, "[shards] %zu/%zu done%s, %.0f s elapsed, ETA %.0f s\n", p.done, p.total,
                     p.failed ? (", " + std::to_string(p.failed) + " failed").c_str() : "", p.elapsed_s, p.eta_s);
    };
    o.notice = [](const std::string& line) { std::fprintf(stderr, "[shards] %s\n", line.c_str()); };
    return o;
}

std::optional<nlohmann::json> run_sharded(const fs::path& dir, const cluster::Manifest& m, const RunnerFlags& f,
                                          bool fork) {
    cluster::RunOptions o = run_options(f, dir);
    if (fork) fork_workers(o);
    if (o.runner == cluster::RunnerKind::slurm && !o.slurm.wait) {
        registry().at(m.job);   // an unknown kind is bad input before anything is written
        cluster::prepare_run(dir, m);
        const cluster::RunSummary s = cluster::run(dir, o);
        if (s.ran == 0) return cluster::merge_run(registry(), dir);   // every shard already has its result
        std::printf("harris-cosim: submitted %zu shard(s) of %s as Slurm array job %s, merge job %s.\n"
                    "`harris-cosim shard status %s` shows what is missing; when both jobs are done, the same\n"
                    "command with --resume renders the report from the merged results without running anything.\n",
                    s.ran, dir.c_str(), s.slurm_array_job.c_str(),
                    s.slurm_merge_job.empty() ? "(none)" : s.slurm_merge_job.c_str(), dir.c_str());
        return std::nullopt;
    }
    return cluster::run_and_merge(registry(), dir, m, o);
}

void run_worker(const fs::path& dir, std::size_t index) {
    cluster::run_shard(registry(), dir, index, {{"harris-cosim", HC_VERSION}});
}

void fork_workers(cluster::RunOptions& o) { o.fork_worker = run_worker; }

}  // namespace hc::tools
