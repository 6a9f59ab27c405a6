// smoke.cpp: see smoke.hpp.
#include "mutation/smoke.hpp"

#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cosim/cosim.hpp"
#include "mutation/mutated_run.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace hc::mutation {

namespace {

std::string str(const json& m, const char* key, const std::string& where) {
    if (!m.contains(key) || !m[key].is_string()) throw InputError(where + ": '" + key + "' must be a string");
    return m[key].get<std::string>();
}

std::string md_code(std::string s) {
    for (auto& c : s)
        if (c == '|') c = '/';
    return "`" + s + "`";
}

}  // namespace

SmokeOutcome run_smoke_mutant(const SmokeMutant* m, const frames::LoadedFrames& lf, const fs::path& work) {
    SmokeOutcome out;
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<FileEdit> edit;
    if (m)
        edit = FileEdit{m->file,
                        [m](std::string text) {
                            const size_t at = text.find(m->find);
                            if (at == std::string::npos || text.find(m->find, at + 1) != std::string::npos)
                                throw InputError("mutation " + m->id + " does not match exactly once in " + m->file);
                            return text.replace(at, m->find.size(), m->replace);
                        },
                        "rtl/" + m->file + " (mutation " + m->id + ")"};
    cosim::GhdlRun run;
    run.frames = lf.frames;
    run.frame_names = lf.names;
    run.summary_json = work / "summary.json";
    run.vcd = work / "mismatch.vcd";
    const MutatedRun r = run_mutated(edit ? &*edit : nullptr, work, {run});
    if (!r.analysed) {
        out.status = "does not analyse";
        return out;
    }
    const StreamOutcome& s = r.streams.front();
    if (s.result) {
        const cosim::Summary& sm = s.result->summary;
        out.status = sm.mismatching_cycles > 0 ? "mismatch" : "pass";
        if (sm.first_mismatch) {
            out.stage = sm.first_mismatch->stage;
            out.signal = sm.first_mismatch->signal;
            out.write = sm.first_mismatch->write;
        }
    } else {
        out.status = "simulator failed: " + s.error;
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

SmokeVerdict judge_smoke(const SmokeMutant& m, const SmokeOutcome& o) {
    SmokeVerdict v{m, o};
    v.caught = o.status == "mismatch";
    v.ok = m.equivalent ? o.status == "pass" : v.caught && o.stage == m.stage;
    return v;
}

SmokeResult tally_smoke(const SmokeOutcome& baseline, std::vector<SmokeVerdict> verdicts) {
    SmokeResult r;
    r.baseline = baseline;
    if (r.baseline.status != "pass") ++r.problems;
    for (const auto& v : verdicts) {
        if (!v.mutant.equivalent) {
            ++r.total;
            r.caught += v.caught;
        }
        if (!v.ok) ++r.problems;
    }
    r.verdicts = std::move(verdicts);
    return r;
}

SmokeList load_smoke_list(const fs::path& p) {
    const std::string what = "mutation list '" + p.string() + "'";
    json j;
    try {
        j = json::parse(util::read_file(p, what));
    } catch (const json::exception& e) {
        throw InputError(what + ": not valid JSON: " + e.what());
    }
    SmokeList c;
    try {   // a value of the wrong type ("equivalent": "yes") is bad input, not a fault
        if (!j.contains("stream") || !j["stream"].is_object()) throw InputError(what + ": 'stream' must be an object");
        const json& s = j["stream"];
        c.stream.pattern = s.value("pattern", "");
        c.stream.size = s.value("size", "");
        c.stream.frames = s.value("frames", 0);
        c.stream.seed = s.value("seed", 1u);
        if (!j.contains("mutants") || !j["mutants"].is_array()) throw InputError(what + ": 'mutants' must be a list");
        for (size_t i = 0; i < j["mutants"].size(); ++i) {
            const json& m = j["mutants"][i];
            const std::string where = what + ": mutants[" + std::to_string(i) + "]";
            c.mutants.push_back({str(m, "id", where), str(m, "kind", where), str(m, "file", where), str(m, "stage", where),
                                 str(m, "find", where), str(m, "replace", where), m.value("equivalent", false)});
        }
    } catch (const json::exception& e) {
        throw InputError(what + ": " + e.what());
    }
    return c;
}

std::string stream_flags(const frames::FrameSource& s) {
    std::string f;
    auto add = [&](const std::string& flag, const std::string& v) { f += (f.empty() ? "" : " ") + flag + " " + v; };
    if (!s.pattern.empty()) add("--pattern", s.pattern);
    if (!s.size.empty()) add("--size", s.size);
    if (s.frames > 0) add("--frames", std::to_string(s.frames));
    if (s.seed != 1) add("--seed", std::to_string(s.seed));
    return f;
}

SmokeResult run_smoke_list(const SmokeList& c, const std::string& only,
                            const std::function<void(const std::string&)>& progress) {
    const frames::LoadedFrames lf = frames::load_frames(c.stream);
    util::ScratchDir scratch("harris-mutate");
    progress("baseline (no mutation) ...");
    const SmokeOutcome baseline = run_smoke_mutant(nullptr, lf, scratch.path() / "baseline");
    std::vector<SmokeVerdict> verdicts;
    for (const auto& m : c.mutants) {
        if (!only.empty() && m.id != only) continue;
        progress(m.id + " " + m.file + ": " + m.kind + " ...");
        verdicts.push_back(judge_smoke(m, run_smoke_mutant(&m, lf, scratch.path() / m.id)));
        const SmokeOutcome& o = verdicts.back().outcome;
        progress(m.id + ": " + o.status + (o.stage.empty() ? "" : ", first stage " + o.stage));
    }
    return tally_smoke(baseline, std::move(verdicts));
}

std::string smoke_markdown(const SmokeList& c, const SmokeResult& r, const std::string& list, const std::string& command) {
    std::ostringstream md;
    md << "# Mutation campaign: the hand-written smoke set\n\n"
       << "Made by `" << command << "` (mutations: `" << list << "`).\n"
       << "Each mutant is one edit of a scratch copy of `rtl/`, co-simulated with GHDL (mcode) against the\n"
       << "unmutated cycle model on the stream `" << stream_flags(c.stream)
       << "`. *Caught* means the run failed; *localised* means the first mismatching stage\n"
       << "it names is the mutated one.\n\n";
    md << "Baseline, unmutated RTL: **" << r.baseline.status << "** (" << std::fixed;
    md.precision(1);
    md << r.baseline.seconds << " s).\n\n";
    md << "| id | kind | file | change | expected stage | result | first stage | signal | write | localised |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    std::ostringstream eq;
    for (const auto& v : r.verdicts) {
        const SmokeMutant& m = v.mutant;
        std::string result;
        if (m.equivalent) {
            result = v.ok ? "not caught (equivalent, as expected)" : "CAUGHT: the mutant is not equivalent";
            eq << "- **" << m.id << "** " << md_code(m.find) << " → " << md_code(m.replace) << ": "
               << (v.ok ? "passes the co-simulation, as it must" : "FAILS the co-simulation") << ".\n";
        } else {
            result = v.caught ? "caught" : "NOT CAUGHT (" + v.outcome.status + ")";
        }
        md << "| " << m.id << " | " << m.kind << " | `" << m.file << "` | " << md_code(m.find) << " → "
           << md_code(m.replace) << " | " << m.stage << " | " << result << " | "
           << (v.outcome.stage.empty() ? "-" : v.outcome.stage) << " | "
           << (v.outcome.signal.empty() ? "-" : md_code(v.outcome.signal)) << " | "
           << (v.outcome.write ? std::to_string(v.outcome.write) : "-") << " | "
           << (m.equivalent ? (v.ok ? "n/a" : "**no**") : (v.ok ? "yes" : "**no**")) << " |\n";
    }
    md << "\n**" << r.caught << " of " << r.total << " non-equivalent mutants caught**; "
       << (r.problems == 0 ? "every one localised to its stage." : std::to_string(r.problems) + " problem(s).") << "\n";
    if (!eq.str().empty())
        md << "\n## Equivalent mutants\n\nThese edits cannot change any register value, so no test can catch "
              "them; the campaign checks that they pass.\n\n"
           << eq.str()
           << "\nM21: `running` only changes when the new response is larger; with `>=` an equal response "
              "replaces `running` by the same value, so every register keeps the same bits.\n";
    return md.str();
}

}  // namespace hc::mutation
