// cli.cpp: the flags several commands share (commands.hpp) and the runner they hand to
// their libraries.
#include <filesystem>
#include <set>

#include "tools/commands.hpp"
#include "tools/registry.hpp"

namespace hc::tools {

namespace {
std::filesystem::path& program() {
    static std::filesystem::path p;
    return p;
}
}  // namespace

void set_program_path(const char* argv0) { program() = cluster::resolve_program(argv0); }

namespace {
std::vector<std::string>& typed_arguments() {
    static std::vector<std::string> a;
    return a;
}
}  // namespace

void set_command_line(int argc, char** argv) {
    typed_arguments().assign(argv + std::min(argc, 1), argv + argc);
}

std::string typed_command_line(const CLI::App* cmd) {
    std::set<std::string> valued, bare;   // the sharding flags of `cmd` (add_runner_flags' group)
    for (const CLI::Option* o : cmd->get_options([](const CLI::Option* o) { return o->get_group() == "Sharding"; }))
        for (const std::string& n : o->get_lnames()) (o->get_expected_max() == 0 ? bare : valued).insert("--" + n);
    std::vector<std::string> kept;
    const std::vector<std::string>& a = typed_arguments();
    for (std::size_t i = 0; i < a.size(); ++i) {
        const std::string name = a[i].substr(0, a[i].find('='));
        if (bare.count(name)) continue;
        if (valued.count(name)) {
            if (a[i].find('=') == std::string::npos) ++i;   // its value follows
            continue;
        }
        kept.push_back(a[i]);
    }
    return util::shell_command_line("harris-cosim", kept);
}

std::string effective_settings(const CLI::App* cmd) {
    std::string out;
    for (const CLI::Option* o : cmd->get_options([](const CLI::Option* o) {
             return o->get_group() != "Sharding" && !o->get_lnames().empty() && o->get_lnames().front() != "help";
         })) {
        std::string v;
        if (o->get_expected_max() == 0) {   // a flag without a value
            v = o->count() > 0 ? "true" : "false";
        } else if (o->count() > 0) {
            for (const std::string& r : o->results()) v += (v.empty() ? "" : " ") + r;
        } else {
            v = o->get_default_str();
        }
        out += o->get_lnames().front() + "=" + v + "\n";
    }
    return out;
}

CLI::Validator whole_number(long min) {
    return CLI::Validator(
        [min](std::string& s) -> std::string {
            std::size_t used = 0;
            long v = 0;
            try {
                v = std::stol(s, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (s.empty() || used != s.size() || v < min)
                return "'" + s + "' is not a whole number >= " + std::to_string(min);
            return {};
        },
        "N >= " + std::to_string(min));
}

void add_frame_source_options(CLI::App* cmd, frames::FrameSource& o) {
    cmd->add_option("images", o.images,
                    "8-bit images streamed as chained frames, in order: files, quoted glob patterns, folders (their "
                    "images sorted by name), or one video file");
    cmd->add_option("--pattern", o.pattern, "synthetic frames: " + pattern_names());
    cmd->add_option("--size", o.size, "WxH: size of synthetic frames, or a centred crop of the frames read (eval scores KITTI frames whole)");
    cmd->add_option("--frames", o.frames,
                    "number of frames: of a pattern (default 3), else the first N frames of the stream (KITTI: L R L R ...)")
        ->check(whole_number(1));
    cmd->add_option("--kitti", o.kitti, "KITTI odometry root (holds sequences/NN); default <data>/kitti");
    cmd->add_option("--sequence", o.sequence, "KITTI sequence")->capture_default_str();
    add_pair_range_option(cmd, o.pairs, "; streamed L R L R ...");
    cmd->add_option("--data", o.data, "data directory (default $HARRIS_COSIM_DATA, else ../shared/data)");
    cmd->add_option("--seed", o.seed, "seed of random patterns")->capture_default_str();
}

void add_pair_range_option(CLI::App* cmd, std::string& range, const std::string& more) {
    const CLI::Validator range_check(
        [](std::string& s) -> std::string {
            try {
                util::parse_range(s, "--pairs");
            } catch (const InputError& e) {
                return e.what();
            }
            return {};
        },
        "");
    cmd->add_option("--pairs", range, "a:b stereo pairs of each sequence (b excluded; a: or :b open)" + more)
        ->check(range_check)
        ->type_name("A:B");
}

void add_rig_options(CLI::App* cmd, frames::RigSource& r, const std::string& use) {
    cmd->add_option("--calib", r.calib,
                    "a rig's calibration (harris-cosim calibrate's calib.yml/.json, or a KITTI-style calib.txt of "
                    "rectified images): " + use);
    cmd->add_option("--left", r.left, "with --calib: the rig's left images (files, quoted glob patterns or folders, sorted by name)");
    cmd->add_option("--right", r.right, "with --calib: the rig's right images, paired with --left in order");
}

void add_commands(CLI::App& app) {
    // in the order --help lists them
    for (auto add : {add_rtl_command, add_model_command, add_golden_command, add_mutate_command, add_verilate_command,
                     add_eval_command, add_sweep_command, add_ranges_command, add_calibrate_command, add_slam_command,
                     add_landmarks_command, add_shard_command})
        add(app);
}

void add_runner_flags(CLI::App* cmd, cluster::RunnerSettings& f) {
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

cluster::JobRunner job_runner(const CLI::App* cmd, cluster::RunnerSettings s, bool single_jobs) {
    const auto given = [cmd](const char* flag) {   // a command without the flag (`shard run`) has not given it
        const CLI::Option* o = cmd->get_option_no_throw(flag);
        return o && o->count() > 0;
    };
    bool any = false;
    for (const char* f : cluster::kShardingFlags) any = any || given(f);
    if (!any && !single_jobs && given("--jobs"))
        throw InputError("--jobs counts the shards run at once: give one of " + cluster::sharding_flags_named() +
                         " to run " + cmd->get_name() + " in shards");
    s.sharded = any;
    return cluster::JobRunner(registry(), std::move(s), program(), HC_VERSION);
}

}  // namespace hc::tools
