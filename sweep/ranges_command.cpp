// ranges_command.cpp: see ranges_command.hpp.
#include "sweep/ranges_command.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cosim/cosim.hpp"
#include "model/util/util.hpp"
#include "model/harris/formats_json.hpp"
#include "sweep/control_induction.hpp"
#include "sweep/datapath_induction.hpp"
#include "sweep/stage_equivalence.hpp"
#include "sweep/sweep_config.hpp"

namespace fs = std::filesystem;

namespace hc::sweep {

namespace {

/// --control-sizes as geometries; InputError for a size the design cannot be built for.
std::vector<Geometry> control_sizes(const RangesCommand& c) {
    std::vector<Geometry> sizes;
    for (const auto& s : c.control_sizes) {
        const auto [w, h] = util::parse_size(s, "--control-sizes");
        sizes.push_back({w, h});
        try {
            sizes.back().validate();
        } catch (const std::invalid_argument& e) {
            throw InputError("ranges: --control-sizes " + s + ": " + e.what());
        }
    }
    return sizes;
}

/// The control induction of `cfg` at each size: a line on stderr each, `js` the JSON array, and
/// the Markdown section returned.
std::string control_induction_section(const RangesCommand& c, const Config& cfg, const std::vector<Geometry>& sizes, nlohmann::json& js) {
    std::vector<ControlInduction> ci;
    js = nlohmann::json::array();
    for (const Geometry& g : sizes) {
        const std::string size = fmt::format("{}x{}", g.width, g.height);
        ci.push_back(prove_control_from_reset(cfg.formats, g,
                                              {.dir = fs::path(c.control_induction) / file_stem(cfg.name) / size, .rtl_dir = c.rtl}));
        const ControlInduction& p = ci.back();
        std::fprintf(stderr, "ranges: %s: control induction %s: %s, %ld queries (prefix %ld, period %ld; the model's control state repeats after %ld writes), %s, %.1f s%s%s\n",
                     cfg.name.c_str(), size.c_str(), eq_verdict_name(p.verdict), p.queries, p.prefix, p.period, p.model_writes,
                     p.recheck.empty() ? "no second solver" : p.recheck.c_str(), p.seconds, p.detail.empty() ? "" : ": ", p.detail.c_str());
        js.push_back({{"size", size}, {"verdict", eq_verdict_name(p.verdict)}, {"prefix", p.prefix}, {"period", p.period},
                      {"queries", p.queries}, {"model_writes", p.model_writes}, {"count_range", {p.count_range.first, p.count_range.second}}, {"registers", p.registers}, {"solver", p.solver}, {"recheck", p.recheck},
                      {"rechecked", p.rechecked}, {"seconds", p.seconds}, {"detail", p.detail}, {"command", p.command}});
    }
    return control_induction_markdown(cfg.name, ci);
}

/// The datapath induction of `cfg` at each size: a line on stderr each, `js` the JSON array,
/// and the Markdown section returned.
std::string datapath_induction_section(const RangesCommand& c, const Config& cfg, const std::vector<Geometry>& sizes, nlohmann::json& js) {
    std::vector<DatapathInduction> di;
    js = nlohmann::json::array();
    for (const Geometry& g : sizes) {
        const std::string size = fmt::format("{}x{}", g.width, g.height);
        di.push_back(prove_datapath_from_reset(cfg.formats, g, {.dir = fs::path(c.datapath_induction) / file_stem(cfg.name) / size, .rtl_dir = c.rtl}));
        const DatapathInduction& p = di.back();
        std::fprintf(stderr, "ranges: %s: datapath induction %s: %s, %ld control classes (the model's run: %ld writes), %s, %.1f s%s%s\n",
                     cfg.name.c_str(), size.c_str(), eq_verdict_name(p.verdict), p.classes, p.model_writes,
                     p.recheck.empty() ? "no second solver" : p.recheck.c_str(), p.seconds, p.detail.empty() ? "" : ": ", p.detail.c_str());
        js.push_back({{"size", size}, {"verdict", eq_verdict_name(p.verdict)}, {"classes", p.classes}, {"model_writes", p.model_writes},
                      {"registers", p.registers}, {"invariants", p.invariants},
                      {"side_conditions", p.side_conditions},
                      {"distinct_side_conditions", p.distinct_side_conditions}, {"solver", p.solver}, {"recheck", p.recheck},
                      {"rechecked", p.rechecked}, {"seconds", p.seconds}, {"detail", p.detail}, {"command", p.command}});
    }
    return datapath_induction_markdown(cfg.name, di);
}

}  // namespace

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
        if (c.stages.empty() && c.control_induction.empty() && c.datapath_induction.empty())
            throw InputError("ranges: --rtl " + c.rtl +
                             " names the VHDL of the stage proofs: give --stages DIR too (or --control-induction DIR, --datapath-induction DIR)");
        for (const auto& f : cosim::rtl_sources(c.rtl))
            if (!fs::is_regular_file(f)) throw InputError("ranges: --rtl " + c.rtl + " has no " + f.filename().string());
    }
    const std::vector<Geometry> sizes = control_sizes(c);
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
        if (!c.control_induction.empty()) md += control_induction_section(c, cfg, sizes, all.back()["control_induction"]) + "\n";
        if (!c.datapath_induction.empty()) md += datapath_induction_section(c, cfg, sizes, all.back()["datapath_induction"]) + "\n";
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
