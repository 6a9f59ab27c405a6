// cmd_sweep.cpp: the flags of `harris-cosim sweep` (sweep/sweep_command.hpp), the bit-width
// exploration (docs/bit-widths.md). Exit status: 0 done (wrapping configurations are
// reported, not failures), 1 an RTL check of a Pareto point failed, 2 bad input, 3 a tool failed.
#include "sweep/sweep_command.hpp"
#include "tools/commands.hpp"

namespace hc::tools {

void add_sweep_command(CLI::App& app) {
    const auto [s, c] = add_command<Sharded<sweep::SweepCommand>>(app, "sweep",
        "Bit-width exploration: per configuration of a JSON sweep spec, recall/precision against OpenCV on KITTI\n"
        "(spec model), correct stereo matches of the landmark chain on Middlebury pairs, overflow audit, yosys\n"
        "synth_xilinx cost (cached); Pareto front, each Pareto point verified on the RTL (GHDL co-simulation +\n"
        "Verilator). Exit status: 0 done, 1 an RTL check failed, 2 bad input, 3 tool failure.\n"
        "--jobs: shards at once; in a single-process run, the synthesis / GHDL processes at once.\n"
        "With " + cluster::sharding_flags_named() + " the configurations run in shards (run directory --run-dir, default <out>/run), then the RTL\n"
        "checks of the merged Pareto front, one shard per check (run directory <run-dir>/checks); --shards counts the\n"
        "configurations' shards only.");
    s->add_option("--config", c->config, "JSON sweep spec (sweep/configs/*.json; see sweep/sweep_config.hpp)")->required();
    s->add_option("--out", c->out, "output directory (sweep.md, sweep.csv, sweep.json, pareto.png)")->capture_default_str();
    s->add_option("--cache", c->cache, "synthesis/RTL-check cache (else $HARRIS_COSIM_SWEEP_CACHE or <build>/sweep-cache)");
    s->add_option("--kitti", c->kitti, "KITTI odometry root (holds sequences/NN); default <data>/kitti");
    s->add_option("--data", c->data, "data directory (default $HARRIS_COSIM_DATA, else ../shared/data)");
    s->add_option("--middlebury", c->middlebury,
                  "Middlebury 2006 half-size folder of the stereo-match column (default <data>/middlebury2006/half)");
    s->add_option("--threads", c->threads, "threads for the accuracy runs (0: all cores)")->check(whole_number(0));
    s->add_option("--backend", c->backend, "GHDL back end of the RTL checks (default: the first built: gcc, llvm, mcode)");
    s->add_option("--regression-set", c->regression_set,
                  "the GHDL checks' streams, one per line as golden/regression-set.txt (the default)");
    s->add_flag("--no-rtl", c->no_rtl, "skip the RTL checks of the Pareto points");
    s->add_flag("--stage-proofs", c->stage_proofs,
                "prove every configuration's datapath stages equal to the model (z3, cvc5; about 25-50 s per configuration, "
                "cached under the synthesis key)");
    s->add_flag("--quiet", c->quiet, "no progress lines");
    c->runner.jobs = 2;
    add_runner_flags(s, c->runner);
    s->callback([c, s] { run_quoting_command_line(s, *c, sweep::run_sweep_command, /*single_jobs=*/true); });
}

}  // namespace hc::tools
