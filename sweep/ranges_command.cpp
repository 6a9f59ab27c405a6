// ranges_command.cpp: see ranges_command.hpp.
#include "sweep/ranges_command.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "cosim/cosim.hpp"
#include "model/util/util.hpp"
#include "model/harris/formats_json.hpp"
#include "sweep/stage_equivalence.hpp"
#include "sweep/sweep_config.hpp"

namespace fs = std::filesystem;

namespace hc::sweep {

void run_ranges_command(const RangesCommand& c) {
    if (!c.config.empty() && !c.spec.empty()) throw InputError("ranges: --config and --spec exclude each other");
    if (!c.propose.empty() && !c.spec.empty())
        throw InputError("ranges: --propose " + c.propose + " proposes the widths of one configuration: give --config, not --spec");
    if (!c.propose.empty()) {
        const fs::path dir = fs::absolute(c.propose).parent_path();
        for (fs::path d = dir; !d.empty(); d = d.parent_path()) {
            if (fs::exists(d) && !fs::is_directory(d)) throw InputError("ranges: --propose " + c.propose + ": " + d.string() + " is not a directory");
            if (fs::exists(d) || d == d.parent_path()) break;
        }
    }
    if (c.pixel_max > 255) throw InputError("ranges: --pixel-max " + std::to_string(c.pixel_max) + " is above 255");
    if (!c.rtl.empty()) {
        if (c.stages.empty()) throw InputError("ranges: --rtl " + c.rtl + " names the VHDL of the stage proofs: give --stages DIR too");
        for (const auto& f : cosim::rtl_sources(c.rtl))
            if (!fs::is_regular_file(f)) throw InputError("ranges: --rtl " + c.rtl + " has no " + f.filename().string());
    }
    std::vector<Config> configs;
    if (!c.spec.empty()) configs = load_sweep_spec(c.spec).configs;
    else configs.push_back({c.config.empty() ? "thesis" : fs::path(c.config).stem().string(),
                            c.config.empty() ? Formats{} : formats_from_file(c.config)});
    RangeOptions ro = c.ro;
    ro.pixel_max = c.pixel_max;
    ro.netlist = !c.no_netlist;
    std::string md;
    nlohmann::json all = nlohmann::json::array();
    std::vector<std::string> lines;
    std::optional<WidthProposal> proposal;
    for (const auto& cfg : configs) {
        if (!c.netlist_dir.empty()) ro.netlist_dir = fs::path(c.netlist_dir) / file_stem(cfg.name);
        const RangeReport r = analyse_ranges(cfg.formats, ro);
        std::fprintf(stderr, "ranges: %s: %s\n", cfg.name.c_str(), r.summary().c_str());
        md += ranges_markdown(cfg.name, r) + "\n";
        nlohmann::json j = range_report_to_json(r);
        j["name"] = cfg.name;
        if (!c.propose.empty()) {
            proposal = propose_widths(r);
            md += proposal_markdown(*proposal) + "\n";
            j["proposal"] = nlohmann::json::parse(formats_to_json(proposal->formats));
        }
        all.push_back(j);
        if (!c.stages.empty()) {
            StageOptions so;
            so.dir = fs::path(c.stages) / file_stem(cfg.name);
            so.config = cfg.name;
            so.rtl_dir = c.rtl;
            const StageEquivalence se = stage_equivalence(cfg.formats, so);
            std::fprintf(stderr, "ranges: %s: stages: %s\n", cfg.name.c_str(), se.summary().c_str());
            for (const auto& p : se.stages)
                if (!p.stimulus.empty()) std::fprintf(stderr, "ranges: %s: %s: counterexample stimulus: %s\n", cfg.name.c_str(),
                                                      kEqStageNames[static_cast<int>(p.stage)], p.stimulus.c_str());
            md += stage_equivalence_markdown(cfg.name, se) + "\n";
            all.back()["stages"] = stage_equivalence_to_json(se);
        }
        if (!c.witnesses.empty())
            for (const auto& w : write_witnesses(cfg.name, r, c.witnesses))
                lines.push_back(w.regression_line(c.set_dir.empty() ? fs::path("golden") : fs::path(c.set_dir)));
    }
    if (proposal) util::write_file_atomic(c.propose, formats_to_json(proposal->formats));
    if (!c.json.empty()) util::write_file_atomic(c.json, all.dump(1) + "\n");
    if (!c.out.empty()) util::write_file_atomic(c.out, md);
    else std::fputs(md.c_str(), stdout);
    for (const auto& l : lines) std::printf("regression-set line: %s\n", l.c_str());
}

}  // namespace hc::sweep
