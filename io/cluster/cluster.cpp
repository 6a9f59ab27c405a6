// cluster.cpp: manifests, shard results, the local and Slurm runners, the merge.
#include "io/cluster/cluster.hpp"

#include "model/util/util.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

extern char** environ;

namespace hc::cluster {

namespace {

std::string slurp(const fs::path& p) {
    try {
        return util::read_file(p);
    } catch (const hc::InputError&) {
        throw hc::InputError("cannot read '" + p.string() + "'");
    }
}

// Temporary file beside the target, then rename: readers see the old file or the whole new one.
void write_atomic(const fs::path& target, const std::string& bytes) { util::write_file_atomic(target, bytes); }

std::string index_name(std::size_t i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%05zu", i);
    return buf;
}

std::string host_name() {
    char buf[256] = {};
    ::gethostname(buf, sizeof buf - 1);
    return buf;
}

// Shell single-quoting for the generated sbatch scripts.
std::string sh_quote(const std::string& s) {
    std::string r = "'";
    for (char c : s) {
        if (c == '\'') r += "'\\''";
        else r += c;
    }
    return r + "'";
}

std::vector<char*> c_argv(std::vector<std::string>& a) {
    std::vector<char*> v;
    for (auto& s : a) v.push_back(s.data());
    v.push_back(nullptr);
    return v;
}

// Starts argv with stdout and stderr appended to `log`; returns the pid.
pid_t spawn_logged(std::vector<std::string> argv, const fs::path& log) {
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    auto args = c_argv(argv);
    pid_t pid = 0;
    const int err = ::posix_spawnp(&pid, args[0], &fa, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (err != 0)
        throw ClusterRunError("cannot start '" + argv[0] + "': " + std::strerror(err));
    return pid;
}

// Forks a copy of this process that calls fn(dir, index) with stdout and stderr appended to
// `log` and stdin from /dev/null, as spawn_logged's worker has them; returns the pid. The
// child exits 0 after fn returns, 3 when it throws.
pid_t fork_logged(const std::function<void(const fs::path&, std::size_t)>& fn, const fs::path& dir,
                  std::size_t index, const fs::path& log) {
    std::fflush(nullptr);   // nothing buffered here is written by the child too
    const pid_t pid = ::fork();
    if (pid < 0) throw ClusterRunError(std::string("cannot fork a worker: ") + std::strerror(errno));
    if (pid > 0) return pid;
    const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    const int in = ::open("/dev/null", O_RDONLY);
    if (out < 0 || in < 0 || ::dup2(out, 1) < 0 || ::dup2(out, 2) < 0 || ::dup2(in, 0) < 0) ::_exit(127);
    ::close(out);
    ::close(in);
    int status = 0;
    try {
        fn(dir, index);
    } catch (const std::exception& e) {
        std::fflush(stdout);   // the message after what the shard printed
        std::fprintf(stderr, "shard %zu: %s\n", index, e.what());
        status = 3;
    } catch (...) {
        std::fflush(stdout);
        std::fprintf(stderr, "shard %zu: unknown exception\n", index);
        status = 3;
    }
    std::fflush(nullptr);
    ::_exit(status);   // no exit handlers or destructors of the parent's state
}

// Whether this process runs one thread only (Linux: /proc/self/task); false when unknown.
bool only_thread() {
    std::error_code ec;
    std::size_t n = 0;
    for (fs::directory_iterator it("/proc/self/task", ec), end; !ec && it != end; it.increment(ec)) ++n;
    return !ec && n == 1;
}

// Runs argv, returns (exit status, stdout). stderr is inherited.
std::pair<int, std::string> capture(std::vector<std::string> argv) {
    int fds[2];
    if (::pipe(fds) != 0) throw ClusterRunError("pipe failed");
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    auto args = c_argv(argv);
    pid_t pid = 0;
    const int err = ::posix_spawnp(&pid, args[0], &fa, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    ::close(fds[1]);
    if (err != 0) {
        ::close(fds[0]);
        throw ClusterRunError("cannot start '" + argv[0] + "': " + std::strerror(err));
    }
    std::string out;
    char buf[4096];
    ssize_t n;
    while ((n = ::read(fds[0], buf, sizeof buf)) > 0) out.append(buf, static_cast<size_t>(n));
    ::close(fds[0]);
    int st = 0;
    ::waitpid(pid, &st, 0);
    const int code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
    return {code, out};
}

double now_s() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

Progress make_progress(std::size_t done, std::size_t total, std::size_t failed, double t0,
                       std::size_t done_at_start) {
    Progress p;
    p.done = done;
    p.total = total;
    p.failed = failed;
    p.elapsed_s = now_s() - t0;
    const std::size_t ran = done - done_at_start;
    const std::size_t left = total - done;
    p.eta_s = ran ? p.elapsed_s / static_cast<double>(ran) * static_cast<double>(left) : 0.0;
    return p;
}

RunSummary run_local(const fs::path& dir, const Manifest& m, const std::vector<std::size_t>& todo,
                     const RunOptions& o) {
    RunSummary s;
    s.shards = m.shards.size();
    s.skipped = m.shards.size() - todo.size();
    const double t0 = now_s();
    const int jobs = std::max(1, o.jobs);
    std::vector<std::size_t> queue(todo.rbegin(), todo.rend());   // pop_back = ascending
    std::map<pid_t, std::size_t> running;
    std::map<std::size_t, int> attempts;
    std::size_t done = s.skipped, failed = 0;
    while (!queue.empty() || !running.empty()) {
        while (!queue.empty() && static_cast<int>(running.size()) < jobs) {
            const std::size_t i = queue.back();
            queue.pop_back();
            std::vector<std::string> argv = o.worker;
            argv.push_back(dir.string());
            argv.push_back(std::to_string(i));
            ++attempts[i];
            running[o.fork_worker && only_thread() ? fork_logged(o.fork_worker, dir, i, log_path(dir, i))
                                                   : spawn_logged(argv, log_path(dir, i))] = i;
            ++s.ran;
        }
        int st = 0;
        const pid_t pid = ::waitpid(-1, &st, 0);
        if (pid < 0) {
            if (errno == EINTR) continue;
            throw ClusterRunError(std::string("waitpid failed: ") + std::strerror(errno));
        }
        auto it = running.find(pid);
        if (it == running.end()) continue;   // a child this runner did not start
        const std::size_t i = it->second;
        running.erase(it);
        const bool ok = WIFEXITED(st) && WEXITSTATUS(st) == 0 && check_result(dir, m, i).state == ResultState::valid;
        if (ok) {
            ++done;
        } else if (attempts[i] <= o.retries) {
            queue.push_back(i);
        } else {
            ++failed;
            s.failed.push_back(i);
        }
        if (o.progress) o.progress(make_progress(done, s.shards, failed, t0, s.skipped));
    }
    std::sort(s.failed.begin(), s.failed.end());
    return s;
}

std::string sbatch_submit(std::vector<std::string> args) {
    args.insert(args.begin(), {"sbatch", "--parsable"});
    auto [code, out] = capture(args);
    if (code != 0) throw ClusterRunError("sbatch failed (status " + std::to_string(code) + ")");
    const auto id = out.substr(0, out.find_first_of(";\n"));
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
        throw ClusterRunError("sbatch printed no job id: '" + out + "'");
    return id;
}

std::vector<std::string> slurm_common_args(const SlurmOptions& so) {
    std::vector<std::string> a;
    if (!so.partition.empty()) a.push_back("--partition=" + so.partition);
    if (!so.account.empty()) a.push_back("--account=" + so.account);
    if (!so.time.empty()) a.push_back("--time=" + so.time);
    if (!so.mem.empty()) a.push_back("--mem=" + so.mem);
    a.push_back("--cpus-per-task=" + std::to_string(std::max(1, so.cpus_per_task)));
    for (const auto& e : so.extra) a.push_back(e);
    return a;
}

/// `exec` of the command `cmd` with the run directory `dir` as its next argument, quoted
/// for sh.
std::string exec_line(const std::vector<std::string>& cmd, const fs::path& dir) {
    std::string sh = "exec";
    for (const auto& a : cmd) {
        sh += ' ';
        sh += sh_quote(a);
    }
    sh += ' ';
    sh += sh_quote(dir.string());
    return sh;
}

/// Until the submitted jobs of `s` have left the queue, polling squeue every poll_s
/// seconds; the shards' progress from their result files.
void wait_for_slurm(const fs::path& dir, const Manifest& m, const RunSummary& s, const RunOptions& o) {
    const double t0 = now_s();
    std::string ids = s.slurm_array_job;
    if (!s.slurm_merge_job.empty()) ids += "," + s.slurm_merge_job;
    std::size_t last_done = s.skipped;
    for (;;) {
        auto [code, out] = capture({"squeue", "--noheader", "--jobs=" + ids, "--format=%i"});
        // squeue exits non-zero once every listed job has left the queue (ids unknown).
        const bool empty = code != 0 || out.find_first_not_of(" \n") == std::string::npos;
        const std::size_t done = m.shards.size() - missing_shards(dir, m).size();
        if (o.progress && (done != last_done || empty))
            o.progress(make_progress(done, s.shards, 0, t0, s.skipped));
        last_done = done;
        if (empty) break;
        std::this_thread::sleep_for(std::chrono::duration<double>(o.slurm.poll_s));
    }
}

RunSummary run_slurm(const fs::path& dir, const Manifest& m, const std::vector<std::size_t>& todo,
                     const RunOptions& o) {
    RunSummary s;
    s.shards = m.shards.size();
    s.skipped = m.shards.size() - todo.size();
    const fs::path sd = dir / "slurm";
    fs::create_directories(sd);
    const fs::path adir = fs::absolute(dir);
    // Array task k runs the k-th missing shard: the map file keeps array indices small
    // (Slurm's MaxArraySize) whatever the shard numbers are.
    const std::string stamp = std::to_string(static_cast<long long>(std::time(nullptr))) + "-" +
                              std::to_string(::getpid());
    const fs::path map_file = sd / ("tasks-" + stamp + ".txt");
    {
        std::string lines;
        for (auto i : todo) lines += std::to_string(i) + "\n";
        write_atomic(map_file, lines);
    }
    const fs::path script = sd / ("array-" + stamp + ".sh");
    {
        std::string sh = "#!/bin/sh\n"
                         "# Generated by harris-cosim: array task k runs the shard on line k+1 of\n"
                         "# the task map.\n"
                         "set -e\n";
        sh += "index=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" ";
        sh += sh_quote(fs::absolute(map_file).string());
        sh += ")\n";
        sh += exec_line(o.worker, adir) + " \"$index\"\n";
        write_atomic(script, sh);
    }
    std::vector<std::string> args = slurm_common_args(o.slurm);
    std::string array = "0-" + std::to_string(todo.size() - 1);
    if (o.slurm.max_parallel > 0) array += "%" + std::to_string(o.slurm.max_parallel);
    args.push_back("--array=" + array);
    args.push_back("--job-name=hc-" + m.job);
    args.push_back("--output=" + (adir / "logs" / "slurm-%A_%a.log").string());
    args.push_back(fs::absolute(script).string());
    s.slurm_array_job = sbatch_submit(args);
    s.ran = todo.size();
    if (!o.merger.empty()) {
        const fs::path ms = sd / ("merge-" + stamp + ".sh");
        write_atomic(ms, "#!/bin/sh\n# Generated by harris-cosim: the merge after the array.\n" + exec_line(o.merger, adir) + '\n');
        std::vector<std::string> margs = slurm_common_args(o.slurm);
        std::string dep = "--dependency=afterok:";
        dep += s.slurm_array_job;
        margs.push_back(dep);
        margs.push_back("--kill-on-invalid-dep=yes");
        margs.push_back("--job-name=hc-" + m.job + "-merge");
        margs.push_back("--output=" + (adir / "logs" / "merge-%j.log").string());
        margs.push_back(fs::absolute(ms).string());
        s.slurm_merge_job = sbatch_submit(margs);
    }
    write_atomic(sd / ("jobs-" + stamp + ".json"),
                 json{{"array", s.slurm_array_job}, {"merge", s.slurm_merge_job}}.dump(2) + "\n");
    if (!o.slurm.wait) return s;

    wait_for_slurm(dir, m, s, o);
    s.failed = missing_shards(dir, m);
    return s;
}

}  // namespace

std::string Manifest::hash() const { return util::hex64(util::fnv1a(to_json().dump())); }

json Manifest::to_json() const {
    return json{{"schema", "harris-cosim.manifest/1"}, {"job", job}, {"common", common}, {"shards", shards}};
}

Manifest Manifest::from_json(const json& j, const std::string& what) {
    if (!j.is_object() || j.value("schema", "") != "harris-cosim.manifest/1" || !j.contains("job") ||
        !j["job"].is_string() || !j.contains("shards") || !j["shards"].is_array())
        throw hc::InputError(what + ": not a harris-cosim manifest");
    Manifest m;
    m.job = j["job"].get<std::string>();
    m.common = j.value("common", json::object());
    for (const auto& s : j["shards"]) m.shards.push_back(s);
    if (m.shards.empty()) throw hc::InputError(what + ": the manifest has no shards");
    return m;
}

fs::path manifest_path(const fs::path& dir) { return dir / "manifest.json"; }
fs::path result_path(const fs::path& dir, std::size_t index) {
    return dir / "shards" / (index_name(index) + ".json");
}
fs::path log_path(const fs::path& dir, std::size_t index) {
    return dir / "logs" / (index_name(index) + ".log");
}

void prepare_run(const fs::path& dir, const Manifest& m) {
    if (m.shards.empty()) throw hc::InputError("job '" + m.job + "' has no shards");
    if (fs::exists(manifest_path(dir))) {
        const Manifest old = read_manifest(dir);
        if (old.hash() != m.hash())
            throw hc::InputError("'" + dir.string() +
                                    "' holds a run of another manifest; choose another directory "
                                    "or remove it");
    }
    fs::create_directories(dir / "shards");
    fs::create_directories(dir / "logs");
    if (!fs::exists(manifest_path(dir))) write_atomic(manifest_path(dir), m.to_json().dump(2) + "\n");
}

Manifest read_manifest(const fs::path& dir) {
    const fs::path p = manifest_path(dir);
    if (!fs::exists(p)) throw hc::InputError("'" + dir.string() + "' holds no manifest.json");
    try {
        return Manifest::from_json(json::parse(slurp(p)), p.string());
    } catch (const json::exception& e) {   // a syntax error, a number out of range (1e400), a key of another type
        throw hc::InputError("'" + p.string() + "' is not a valid manifest: " + e.what());
    }
}

namespace {

// The digest a result carries: of its compact JSON without the "digest" key. nlohmann's
// objects keep their keys sorted and its numbers are written so that they read back to the
// same value, so a parsed file gives the bytes it was digested from.
std::string content_digest(json j) {
    j.erase("digest");
    return util::hex64(util::fnv1a(j.dump()));
}

}  // namespace

void write_result(const fs::path& dir, const ShardResult& r) {
    json j{{"schema", "harris-cosim.shard/1"}, {"job", r.job},           {"index", r.index},
           {"manifest", r.manifest_hash},     {"provenance", r.provenance}, {"data", r.data}};
    j["digest"] = content_digest(j);
    write_atomic(result_path(dir, r.index), j.dump(1) + "\n");
}

ResultCheck check_result(const fs::path& dir, const Manifest& m, std::size_t index) {
    const fs::path p = result_path(dir, index);
    ResultCheck c;
    if (!fs::exists(p)) return c;
    c.state = ResultState::damaged;
    json j;
    try {
        j = json::parse(slurp(p));
    } catch (const json::exception& e) {   // truncated, or a syntax error, or a number out of range
        c.why = std::string("does not parse: ") + e.what();
        return c;
    }
    if (!j.is_object() || j.value("schema", "") != "harris-cosim.shard/1" || !j.contains("data")) {
        c.why = "is not a shard result";
        return c;
    }
    if (!j.contains("digest") || !j["digest"].is_string()) {
        c.why = "carries no digest of its content";
        return c;
    }
    if (const std::string d = content_digest(j); d != j["digest"].get<std::string>()) {
        c.why = "does not match its digest (" + j["digest"].get<std::string>() + " recorded, " + d +
                " computed from its content)";
        return c;
    }
    ShardResult r;
    try {
        r.job = j.value("job", "");
        r.index = j.value("index", std::size_t{0});
        r.manifest_hash = j.value("manifest", "");
        r.provenance = j.value("provenance", json::object());
    } catch (const json::exception& e) {   // a key of another type: written so, then digested
        throw hc::InputError("'" + p.string() + "' is not a shard result: " + e.what());
    }
    r.data = std::move(j["data"]);
    if (r.job != m.job || r.index != index || r.manifest_hash != m.hash())
        throw hc::InputError("'" + p.string() + "' belongs to another run (job '" + r.job +
                                "', manifest " + r.manifest_hash + ")");
    c.state = ResultState::valid;
    c.result = std::move(r);
    return c;
}

std::optional<ShardResult> read_result(const fs::path& dir, const Manifest& m, std::size_t index) {
    ResultCheck c = check_result(dir, m, index);
    if (c.state == ResultState::damaged)
        throw hc::InputError("'" + result_path(dir, index).string() + "' is damaged: it " + c.why +
                                "; --resume sets it aside and runs shard " + std::to_string(index) + " again");
    return std::move(c.result);
}

std::vector<std::size_t> missing_shards(const fs::path& dir, const Manifest& m) {
    std::vector<std::size_t> v;
    for (std::size_t i = 0; i < m.shards.size(); ++i)
        if (check_result(dir, m, i).state != ResultState::valid) v.push_back(i);
    return v;
}

std::vector<SetAside> set_aside_damaged(const fs::path& dir, const Manifest& m) {
    std::vector<SetAside> moved;
    for (std::size_t i = 0; i < m.shards.size(); ++i) {
        const ResultCheck c = check_result(dir, m, i);
        if (c.state != ResultState::damaged) continue;
        const fs::path p = result_path(dir, i);
        fs::path kept;
        for (int k = 1;; ++k) {
            kept = p.string() + ".damaged-" + std::to_string(k);
            if (!fs::exists(kept)) break;
        }
        fs::rename(p, kept);
        moved.push_back({i, kept, c.why});
        std::ofstream log(log_path(dir, i), std::ios::app);
        log << "harris-cosim: the result of shard " << i << " was damaged (it " << c.why << "); kept as " << kept.string()
            << ", the shard runs again\n";
    }
    return moved;
}

RunSummary run(const fs::path& dir, const RunOptions& o) {
    const Manifest m = read_manifest(dir);
    if (o.worker.empty()) throw hc::InputError("no worker command to run the shards");
    std::vector<SetAside> moved = set_aside_damaged(dir, m);
    for (const SetAside& a : moved)
        if (o.notice)
            o.notice("shard " + std::to_string(a.index) + ": its result was damaged (it " + a.why + "); kept as " +
                     a.kept.string() + ", the shard runs again");
    const auto todo = missing_shards(dir, m);
    RunSummary s;
    if (todo.empty()) {
        s.shards = s.skipped = m.shards.size();
    } else {
        s = o.runner == RunnerKind::local ? run_local(dir, m, todo, o) : run_slurm(dir, m, todo, o);
    }
    s.set_aside = std::move(moved);
    return s;
}

void JobRegistry::add(ShardJob j) {
    const std::string n = j.name;
    jobs_[n] = std::move(j);
}

const ShardJob& JobRegistry::at(const std::string& name) const {
    auto it = jobs_.find(name);
    if (it == jobs_.end()) {
        std::string known;
        for (const auto& [k, v] : jobs_) known += (known.empty() ? "" : ", ") + k;
        throw hc::InputError("unknown job kind '" + name + "' (known: " + known + ")");
    }
    return it->second;
}

std::vector<std::string> JobRegistry::names() const {
    std::vector<std::string> v;
    for (const auto& [k, x] : jobs_) v.push_back(k);
    return v;
}

void run_shard(const JobRegistry& reg, const fs::path& dir, std::size_t index, const json& tool_versions) {
    const Manifest m = read_manifest(dir);
    if (index >= m.shards.size())
        throw hc::InputError("shard " + std::to_string(index) + " does not exist: '" + dir.string() +
                                "' has " + std::to_string(m.shards.size()) + " shards");
    const ShardJob& job = reg.at(m.job);
    const double t0 = now_s();
    const std::clock_t c0 = std::clock();
    ShardResult r;
    r.job = m.job;
    r.index = index;
    r.manifest_hash = m.hash();
    r.data = job.run(m.common, m.shards[index], index);
    r.provenance = {{"tools", tool_versions},
                    {"host", host_name()},
                    {"cpu_s", static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC},
                    {"wall_s", now_s() - t0}};
    write_result(dir, r);
}

json merge(const JobRegistry& reg, const fs::path& dir) {
    const Manifest m = read_manifest(dir);
    const ShardJob& job = reg.at(m.job);
    std::vector<json> data;
    std::vector<std::size_t> missing;
    for (std::size_t i = 0; i < m.shards.size(); ++i) {
        auto r = read_result(dir, m, i);
        if (!r) missing.push_back(i);
        else data.push_back(std::move(r->data));
    }
    if (!missing.empty()) {
        std::string list;
        for (auto i : missing) list += (list.empty() ? "" : ", ") + std::to_string(i);
        throw hc::InputError("'" + dir.string() + "': shards without a result: " + list +
                                " (run again with --resume)");
    }
    return job.merge(m.common, data);
}

json run_in_process(const JobRegistry& reg, const Manifest& m) {
    const ShardJob& job = reg.at(m.job);
    std::vector<json> data;
    for (std::size_t i = 0; i < m.shards.size(); ++i) data.push_back(job.run(m.common, m.shards[i], i));
    return job.merge(m.common, data);
}

std::vector<std::pair<long, long>> split_range(long first, long last, int k) {
    if (last < first || k < 1) throw hc::InputError("cannot split [" + std::to_string(first) + ", " +
                                                       std::to_string(last) + ") into " +
                                                       std::to_string(k) + " parts");
    const long n = last - first;
    const long parts = std::min<long>(k, std::max<long>(n, 1));
    std::vector<std::pair<long, long>> v;
    long a = first;
    for (long i = 0; i < parts; ++i) {
        const long len = n / parts + (i < n % parts ? 1 : 0);
        v.emplace_back(a, a + len);
        a += len;
    }
    return v;
}

std::vector<std::pair<long, long>> split_items(long n, int k) {
    if (n <= 0) return {};
    return split_range(0, n, k <= 0 || k > n ? static_cast<int>(n) : k);
}

fs::path merged_path(const fs::path& dir) { return dir / "merged.json"; }

json merge_run(const JobRegistry& reg, const fs::path& dir) {
    json merged = merge(reg, dir);
    util::write_file_atomic(merged_path(dir), merged.dump(1) + "\n");
    return merged;
}

json run_and_merge(const JobRegistry& reg, const fs::path& dir, const Manifest& m, const RunOptions& o) {
    reg.at(m.job);   // an unknown kind is bad input before anything is written
    prepare_run(dir, m);
    const RunSummary s = run(dir, o);
    if (!s.failed.empty()) {
        std::string which;
        for (std::size_t i : s.failed) which += (which.empty() ? "" : ", ") + std::to_string(i);
        throw ClusterRunError(std::to_string(s.failed.size()) + " of " + std::to_string(s.shards) +
                              " shard(s) of " + dir.string() + " have no result (" + which +
                              "; logs in " + (dir / "logs").string() +
                              "); the same command resumes and runs only those");
    }
    return merge_run(reg, dir);
}

}  // namespace hc::cluster
