// cmd_mutate.cpp: `harris-cosim mutate`: the mutation campaign. Each single-point mutation of
// tools/mutations.json is applied to a scratch copy of rtl/, analysed with GHDL's mcode back
// end and co-simulated against the (unmutated) cycle model. A mutant passes the campaign
// when the co-simulation fails and names the mutated stage as the first mismatching one;
// a mutant marked equivalent passes when the co-simulation finds nothing. The result is a
// Markdown table (docs/mutation-campaign.md).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "commands.hpp"
#include "frames.hpp"
#include "process.hpp"

namespace hc::tools {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream f(p);
    if (!f) throw InputError("cannot read '" + p.string() + "'");
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> v;
    std::stringstream ss(s);
    std::string x;
    while (std::getline(ss, x, sep))
        if (!x.empty()) v.push_back(x);
    return v;
}

std::string md_code(std::string s) {
    for (auto& c : s)
        if (c == '|') c = '/';
    return "`" + s + "`";
}

struct Outcome {
    bool pass = false;
    std::string status, stage, signal;
    long write = 0;
    double seconds = 0;
};

/// Applies the mutation (or none), analyses and co-simulates; reads the summary.
Outcome run_one(const json* m, const std::vector<std::string>& stream, const fs::path& work) {
    Outcome out;
    const auto t0 = std::chrono::steady_clock::now();
    fs::remove_all(work);
    fs::create_directories(work / "rtl");
    fs::create_directories(work / "ghdl-mcode");
    const fs::path src = HC_SOURCE_DIR;
    for (const auto& e : fs::directory_iterator(src / "rtl")) fs::copy_file(e.path(), work / "rtl" / e.path().filename());
    if (m) {
        const fs::path f = work / "rtl" / (*m)["file"].get<std::string>();
        std::string text = slurp(f);
        const std::string find = (*m)["find"], repl = (*m)["replace"];
        const size_t at = text.find(find);
        if (at == std::string::npos || text.find(find, at + 1) != std::string::npos)
            throw InputError("mutation " + (*m)["id"].get<std::string>() + " does not match exactly once in " +
                             f.filename().string());
        text.replace(at, find.size(), repl);
        write_file_atomic(f, text);
    }
    std::vector<std::string> ana = {HC_GHDL_MCODE, "-a", "--std=08", "--workdir=" + (work / "ghdl-mcode").string()};
    for (const auto& stem : split(HC_RTL_ORDER, ',')) ana.push_back((work / "rtl" / (stem + ".vhd")).string());
    ana.push_back(std::string(HC_SIM_DIR) + "/hc_bridge_pkg.vhd");
    ana.push_back((src / "cosim" / "harris_top_tb.vhd").string());
    const fs::path log = work / "log.txt";
    if (run_process(ana, {}, log.string()) != 0) {
        out.status = "does not analyse";
        return out;
    }
    fs::create_symlink(std::string(HC_SIM_DIR) + "/libhc_bridge.so", work / "libhc_bridge.so");
    std::vector<std::string> sim = {fs::read_symlink("/proc/self/exe").string(), "rtl", "--backend", "mcode",
                                    "--sim-dir", work.string(), "--quiet", "--json", (work / "summary.json").string(),
                                    "--vcd", (work / "mismatch.vcd").string()};
    sim.insert(sim.end(), stream.begin(), stream.end());
    const int rc = run_process(sim, {}, log.string());
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!fs::exists(work / "summary.json")) {
        out.status = "simulator failed (status " + std::to_string(rc) + ")";
        return out;
    }
    const json j = json::parse(slurp(work / "summary.json"));
    out.status = j.at("status");
    if (j.contains("first_mismatch")) {
        out.stage = j["first_mismatch"]["stage"];
        out.write = j["first_mismatch"]["write"];
        const std::string rep = j["first_mismatch"]["report"];
        const auto p = rep.find("signal     : ");
        if (p != std::string::npos) out.signal = rep.substr(p + 13, rep.find(' ', p + 13) - p - 13);
    }
    return out;
}

}  // namespace

void add_mutate_command(CLI::App& app) {
    struct Opts {
        std::string list = std::string(HC_SOURCE_DIR) + "/tools/mutations.json";
        std::string report;
        std::string only;
    };
    auto o = std::make_shared<Opts>();
    CLI::App* cmd = app.add_subcommand(
        "mutate",
        "Mutation campaign: apply each single-point RTL mutation to a scratch copy, co-simulate it (GHDL mcode)\n"
        "against the cycle model, and check the co-simulation catches it and names the mutated stage first.\n"
        "Exit status 0 when every mutant is caught and localised (equivalent ones pass).");
    cmd->add_option("--mutations", o->list, "mutation list (JSON)")->capture_default_str();
    cmd->add_option("--report", o->report, "write the Markdown table here (e.g. docs/mutation-campaign.md)");
    cmd->add_option("--only", o->only, "run only the mutant with this id");
    cmd->callback([o]() {
        const json cfg = json::parse(slurp(o->list));
        const std::vector<std::string> stream = cfg.at("stream").get<std::vector<std::string>>();
        std::string tmpl = (fs::temp_directory_path() / "harris-mutate-XXXXXX").string();
        if (!::mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a scratch directory");
        const fs::path scratch = tmpl;
        std::ostringstream md;
        md << "# Mutation campaign\n\n"
           << "Made by `harris-cosim mutate --report docs/mutation-campaign.md` (mutations: `tools/mutations.json`).\n"
           << "Each mutant is one edit of a scratch copy of `rtl/`, co-simulated with GHDL (mcode) against the\n"
           << "unmutated cycle model on the stream `" << [&] {
                  std::string s;
                  for (const auto& a : stream) s += (s.empty() ? "" : " ") + a;
                  return s;
              }() << "`. *Caught* means the run failed; *localised* means the first mismatching stage\n"
           << "it names is the mutated one.\n\n";
        int failures = 0, caught = 0, total = 0;
        std::fprintf(stderr, "[mutate] baseline (no mutation) ...\n");
        const Outcome base = run_one(nullptr, stream, scratch / "baseline");
        md << "Baseline, unmutated RTL: **" << base.status << "** (" << std::fixed;
        md.precision(1);
        md << base.seconds << " s).\n\n";
        if (base.status != "pass") ++failures;
        md << "| id | kind | file | change | expected stage | result | first stage | signal | write | localised |\n"
           << "|---|---|---|---|---|---|---|---|---|---|\n";
        std::ostringstream eq;
        for (const auto& m : cfg.at("mutants")) {
            const std::string id = m["id"];
            if (!o->only.empty() && id != o->only) continue;
            const bool equivalent = m.value("equivalent", false);
            std::fprintf(stderr, "[mutate] %s %s: %s ...\n", id.c_str(), m["file"].get<std::string>().c_str(),
                         m["kind"].get<std::string>().c_str());
            const Outcome r = run_one(&m, stream, scratch / id);
            bool ok;
            std::string result;
            if (equivalent) {
                ok = r.status == "pass";
                result = ok ? "not caught (equivalent, as expected)" : "CAUGHT: the mutant is not equivalent";
                eq << "- **" << id << "** " << md_code(m["find"]) << " → " << md_code(m["replace"]) << ": "
                   << (ok ? "passes the co-simulation, as it must" : "FAILS the co-simulation") << ".\n";
            } else {
                ++total;
                const bool was_caught = r.status == "mismatch";
                caught += was_caught;
                ok = was_caught && r.stage == m["stage"];
                result = was_caught ? "caught" : ("NOT CAUGHT (" + r.status + ")");
            }
            if (!ok) ++failures;
            md << "| " << id << " | " << m["kind"].get<std::string>() << " | `" << m["file"].get<std::string>()
               << "` | " << md_code(m["find"]) << " → " << md_code(m["replace"]) << " | " << m["stage"].get<std::string>()
               << " | " << result << " | " << (r.stage.empty() ? "-" : r.stage) << " | "
               << (r.signal.empty() ? "-" : md_code(r.signal)) << " | " << (r.write ? std::to_string(r.write) : "-")
               << " | " << (equivalent ? (ok ? "n/a" : "**no**") : (ok ? "yes" : "**no**")) << " |\n";
            std::fprintf(stderr, "[mutate] %s: %s%s%s\n", id.c_str(), result.c_str(),
                         r.stage.empty() ? "" : ", first stage ", r.stage.c_str());
        }
        md << "\n**" << caught << " of " << total << " non-equivalent mutants caught**; "
           << (failures == 0 ? "every one localised to its stage." : std::to_string(failures) + " problem(s).")
           << "\n";
        if (!eq.str().empty())
            md << "\n## Equivalent mutants\n\nThese edits cannot change any register value, so no test can catch "
                  "them; the campaign checks that they pass.\n\n"
               << eq.str()
               << "\nM21: `running` only changes when the new response is larger; with `>=` an equal response "
                  "replaces `running` by the same value, so every register keeps the same bits.\n";
        std::error_code ec;
        fs::remove_all(scratch, ec);
        if (!o->report.empty()) write_file_atomic(o->report, md.str());
        else std::printf("%s", md.str().c_str());
        std::printf("harris-cosim mutate: %d of %d mutants caught, %d problem(s)\n", caught, total, failures);
        if (failures) throw CLI::RuntimeError(1);
    });
}

}  // namespace hc::tools
