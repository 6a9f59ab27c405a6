// cmd_ranges.cpp: `harris-cosim ranges`: the derived range of every datapath register of one
// configuration (--config) or of every configuration of a sweep spec (--spec), for every
// input: proven safe, wraps (with a witness window), or open (sweep/ranges.hpp).
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "model/harris/formats_json.hpp"
#include "sweep/ranges.hpp"
#include "sweep/sweep_config.hpp"
#include "tools/commands.hpp"
#include "io/util/util.hpp"

namespace hc::tools {

namespace fs = std::filesystem;

void add_ranges_command(CLI::App& app) {
    struct Opts {
        std::string config, spec, witnesses, set_dir, json, out;
        int pixel_max = 255;
        sweep::RangeOptions ro;
        bool no_netlist = false;
        std::string netlist_dir;
    };
    const auto [cmd, o] = add_command<Opts>(app, "ranges",
        "Derived ranges of every datapath register for every input: an interval bound through the model's\n"
        "stage functions; where it does not fit, a search for a pixel window that wraps the register, then z3\n"
        "on the model's arithmetic; and every register of the stage chain asked by z3 on GHDL's netlist.\n"
        "Each register is proven (cannot wrap), wraps (witness window) or open (bound, best value reached).\n"
        "z3 is limited by its resource limit (rlimit), so verdicts do not depend on the machine's speed.");
    cmd->add_option("--config", o->config, "JSON file of bit widths and shifts (default: the thesis's)");
    cmd->add_option("--spec", o->spec, "sweep spec (sweep/configs/bit-widths.json): every configuration in it");
    cmd->add_option("--witnesses", o->witnesses, "write each witness window as a PGM stimulus and its --config file here");
    cmd->add_option("--set-dir", o->set_dir, "print the witnesses' regression-set lines relative to this directory (default: golden)")
        ->capture_default_str();
    cmd->add_option("--json", o->json, "the reports as JSON");
    cmd->add_option("--out", o->out, "the reports as Markdown (default: stdout)");
    cmd->add_option("--pixel-max", o->pixel_max, "pixels in [0, N]")->capture_default_str()->check(whole_number(1));
    cmd->add_option("--search-windows", o->ro.search_windows, "windows the witness search scores per register and side, at most")
        ->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_option("--solver-rlimit", o->ro.solver_rlimit, "z3 resource units for the model route, per configuration (0: none)")
        ->capture_default_str()->check(CLI::NonNegativeNumber);
    cmd->add_option("--query-rlimit", o->ro.query_rlimit, "z3 resource units per query of the model route")
        ->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_option("--netlist-budget", o->ro.netlist_budget, "z3 resource units for the netlist route, per configuration")
        ->capture_default_str()->check(CLI::NonNegativeNumber);
    cmd->add_option("--netlist-query-rlimit", o->ro.netlist_query_rlimit, "z3 resource units per query of the netlist route")
        ->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_flag("--no-netlist", o->no_netlist, "skip the netlist route (GHDL, yosys, z3 on the synthesised stage chain)");
    cmd->add_option("--netlist-dir", o->netlist_dir,
                    "keep the netlists (GHDL's Verilog, the yosys scripts, the SMT-LIB) here, one folder per configuration");
    cmd->callback([o]() {
        if (!o->config.empty() && !o->spec.empty()) throw InputError("ranges: --config and --spec exclude each other");
        if (o->pixel_max > 255) throw InputError("ranges: --pixel-max " + std::to_string(o->pixel_max) + " is above 255");
        std::vector<sweep::Config> configs;
        if (!o->spec.empty()) configs = sweep::load_sweep_spec(o->spec).configs;
        else configs.push_back({o->config.empty() ? "thesis" : fs::path(o->config).stem().string(),
                                o->config.empty() ? Formats{} : formats_from_file(o->config)});
        sweep::RangeOptions ro = o->ro;
        ro.pixel_max = o->pixel_max;
        ro.netlist = !o->no_netlist;
        std::string md;
        nlohmann::json all = nlohmann::json::array();
        std::vector<std::string> lines;
        for (const auto& c : configs) {
            if (!o->netlist_dir.empty()) ro.netlist_dir = fs::path(o->netlist_dir) / sweep::file_stem(c.name);
            const sweep::RangeReport r = sweep::analyse_ranges(c.formats, ro);
            std::fprintf(stderr, "ranges: %s: %s\n", c.name.c_str(), r.summary().c_str());
            md += sweep::ranges_markdown(c.name, r) + "\n";
            nlohmann::json j = sweep::range_report_to_json(r);
            j["name"] = c.name;
            all.push_back(j);
            if (!o->witnesses.empty())
                for (const auto& w : sweep::write_witnesses(c.name, r, o->witnesses))
                    lines.push_back(w.regression_line(o->set_dir.empty() ? fs::path("golden") : fs::path(o->set_dir)));
        }
        if (!o->json.empty()) util::write_file_atomic(o->json, all.dump(1) + "\n");
        if (!o->out.empty()) util::write_file_atomic(o->out, md);
        else std::fputs(md.c_str(), stdout);
        for (const auto& l : lines) std::printf("regression-set line: %s\n", l.c_str());
    });
}

}  // namespace hc::tools
