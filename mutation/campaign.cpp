// mutants.cpp: see mutants.hpp.
#include "mutation/campaign.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "cosim/cosim.hpp"
#include "cosim/ghdl_verilog.hpp"
#include "model/harris/harris_pkg.hpp"
#include "mutation/mutated_run.hpp"
#include "mutation/proof_steps.hpp"
#include "model/util/util.hpp"

namespace hc::mutation {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string stem(const std::string& file) { return fs::path(file).stem().string(); }

void say(const Options& o, const std::string& s) {
    if (o.progress) o.progress(s);
}

/// The edit `m` makes of its rtl/ file.
FileEdit edit_of(const Mutant& m) {
    return {m.file, [&m](const std::string& text) { return m.apply(text); }, "rtl/" + m.file};
}

/// The first line of a log that GHDL marks as an error (or the log's tail).
std::string first_error(const fs::path& log) {
    std::istringstream in(util::log_tail(log, 4000));
    std::string line;
    while (std::getline(in, line))
        if (line.find("error") != std::string::npos || line.find("failure") != std::string::npos) return line;
    return util::log_tail(log, 200);
}

/// GHDL stopped in elaboration (a bound or length check on the design's constants failing
/// while the hierarchy is built): the design never ran a cycle.
bool failed_in_elaboration(const fs::path& log) {
    const std::string t = util::log_tail(log, 8000);
    return t.find("error during elaboration") != std::string::npos || t.find("from: Elaboration of design") != std::string::npos;
}

/// What one stimulus's co-simulation says of a mutant: "" (it passes), "mismatch",
/// "metavalue" (a failing run with metavalues), or "simulator failed: <its first error>" (a
/// run that is incomplete counts as failing).
std::string kill_reason(const StreamOutcome& s) {
    if (!s.result) return "simulator failed: " + first_error(s.log);
    const cosim::Summary& sm = s.result->summary;
    if (sm.pass() && sm.complete) return "";
    return sm.metavalue_elements > 0 ? "metavalue" : "mismatch";
}

const frames::LoadedFrames& frames_of(const Stimulus& s) {
    static std::map<std::string, frames::LoadedFrames> cache;
    const std::string key = to_json(s).dump();
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, frames::load_frames(s.source)).first;
    return it->second;
}

/// The generics a proof gives the entity in `file`: the smallest geometry, where it has one.
std::vector<std::string> proof_generics(const fs::path& file) {
    const std::string t = util::read_file(file);
    const size_t port = t.find("port");
    const std::string head = t.substr(0, port);
    std::vector<std::string> g;
    if (head.find("IMG_WIDTH") != std::string::npos) g.push_back(fmt::format("-gIMG_WIDTH={}", Geometry::min_width));
    if (head.find("IMG_HEIGHT") != std::string::npos) g.push_back(fmt::format("-gIMG_HEIGHT={}", Geometry::min_height));
    return g;
}

/// Reads gold.v and gate.v as modules `gold` and `gate`. Flattened; or, with `evert` (a
/// mutant of the top entity's own file, whose instances are the same on both sides), each
/// instance of another entity is cut out and its ports become the module's (its inputs
/// outputs compared like the others, its outputs inputs shared by both sides).
std::string load_script(const std::string& entity, bool evert) {
    std::string s;
    for (const char* side : {"gold", "gate"})
        s += fmt::format("read_verilog {0}.v\nhierarchy -top {1}\nproc\n{2}opt_clean\nrename {1} {0}\ndesign -stash {0}\n",
                         side, entity,
                         evert ? fmt::format("expose -evert {0}/c:*\ndelete {0} %n\n", entity) : std::string("flatten\n"));
    s += "design -copy-from gold -as gold gold\ndesign -copy-from gate -as gate gate\nasync2sync\n";
    return s;
}

}  // namespace

std::vector<Mutant> generate_all(const fs::path& rtl_dir) {
    std::vector<Mutant> all;
    for (const auto& p : cosim::rtl_sources(rtl_dir)) {
        auto v = generate_mutants(p.filename().string(), util::read_file(p));
        all.insert(all.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
    }
    return all;
}

std::vector<Mutant> select(const std::vector<Mutant>& all, const Selection& s) {
    for (const auto& c : s.classes) {
        bool known = false;
        for (auto k : all_classes()) known = known || c == class_name(k);
        if (!known) throw InputError("unknown mutant class '" + c + "' (arith, rel, logic, negate, literal, slice, resize, shift, stuck, enable)");
    }
    for (const auto& f : s.files)
        if (std::none_of(all.begin(), all.end(), [&](const auto& m) { return m.file == f; }))
            throw InputError("no generated mutant in file '" + f + "' (a file of rtl/, e.g. sobel_x.vhd)");
    for (const auto& n : s.only)
        if (std::none_of(all.begin(), all.end(), [&](const auto& m) { return m.name().rfind(n, 0) == 0; }))
            throw InputError("no generated mutant is named '" + n + "' (see mutate --generate --list)");
    std::vector<Mutant> out;
    for (const auto& m : all) {
        const bool cls = s.classes.empty() ||
                         std::find(s.classes.begin(), s.classes.end(), class_name(m.cls)) != s.classes.end();
        const bool file = s.files.empty() || std::find(s.files.begin(), s.files.end(), m.file) != s.files.end();
        const bool name = s.only.empty() ||
                          std::any_of(s.only.begin(), s.only.end(), [&](const auto& n) { return m.name().rfind(n, 0) == 0; });
        if (cls && file && name) out.push_back(m);
    }
    return out;
}

std::string proof_entity(const std::string& file) {
    const std::string e = stem(file);
    return e == "harris_pkg" ? "harris_top" : e;
}

std::string fate_name(Fate f) {
    for (const auto& [fate, name] : fate_names)
        if (fate == f) return std::string(name);
    throw InternalError("a verdict without a name");
}

std::optional<Fate> fate_from_name(std::string_view name) {
    for (const auto& [fate, n] : fate_names)
        if (n == name) return fate;
    return std::nullopt;
}

json to_json(const Stimulus& s) {
    return {{"name", s.name},       {"images", s.source.images}, {"pattern", s.source.pattern},
            {"size", s.source.size}, {"frames", s.source.frames}, {"kitti", s.source.kitti},
            {"sequence", s.source.sequence}, {"pairs", s.source.pairs}, {"seed", s.source.seed},
            {"idle_every", s.idle_every}};
}

Stimulus stimulus_from_json(const json& j) {
    try {
        Stimulus s;
        s.name = j.at("name").get<std::string>();
        s.source.images = j.at("images").get<std::vector<std::string>>();
        s.source.pattern = j.at("pattern").get<std::string>();
        s.source.size = j.at("size").get<std::string>();
        s.source.frames = j.at("frames").get<int>();
        s.source.kitti = j.at("kitti").get<std::string>();
        s.source.sequence = j.at("sequence").get<std::string>();
        s.source.pairs = j.at("pairs").get<std::string>();
        s.source.seed = j.at("seed").get<std::uint32_t>();
        s.idle_every = j.at("idle_every").get<int>();
        return s;
    } catch (const json::exception& e) {
        throw InputError(std::string("bad stimulus in a mutant run's parameters: ") + e.what());
    }
}

namespace {
/// A stream of a synthetic pattern, named <pattern>_<size>x<frames>[_idle<n>][_seed<s>].
Stimulus pattern_stimulus(const std::string& pattern, const std::string& size, int frames, int idle_every,
                          std::uint32_t seed) {
    Stimulus s;
    s.name = pattern + "_" + size + "x" + std::to_string(frames) +
             (idle_every ? "_idle" + std::to_string(idle_every) : "") + (seed != 1 ? "_seed" + std::to_string(seed) : "");
    s.source.pattern = pattern;
    s.source.size = size;
    s.source.frames = frames;
    s.source.seed = seed;
    s.idle_every = idle_every;
    return s;
}
}  // namespace

Stimulus quick_stimulus() {
    Stimulus s = pattern_stimulus("blocks", "24x16", 2, 0, 1);
    s.name = "quick_" + s.name;
    return s;
}

std::vector<Stimulus> long_stimuli(const fs::path& data_dir) {
    // more chained frames of noise, an idle cycle every 3 writes (registers must hold)
    std::vector<Stimulus> v = {pattern_stimulus("random", "24x16", 4, 3, 7)};
    // from the regression set, in its order: random 40x30 with idle cycles (a period maximum
    // where find-max's period ends), half-turn symmetric blobs (equal neighbours at the
    // local-maximum test), and extremes on an odd width with idle cycles (the widest values)
    for (const auto& r : util::read_regression_set(cosim::rtl_dir().parent_path() / "golden" / "regression-set.txt"))
        if (r.stem() == "random_40x30" || r.stem() == "twins_40x30" || r.stem() == "extremes_33x21")
            v.push_back(pattern_stimulus(r.pattern, r.size(), r.frames, r.idle_every, 1));
    // a response equal to its threshold: in frame 2 of this stream one response holds exactly
    // the threshold then in force (found with the cycle model; a test checks it)
    v.push_back(pattern_stimulus("blocks", "33x21", 3, 0, 18));
    if (!data_dir.empty()) {
        Stimulus k;
        k.name = "kitti01_L0R0_32x24";
        k.source.kitti = (data_dir / "kitti").string();
        k.source.sequence = "01";
        k.source.pairs = "0:1";
        k.source.size = "32x24";
        v.push_back(k);
    }
    return v;
}

json to_json(const Result& r) {
    return {{"name", r.name},
            {"file", r.file},
            {"entity", r.entity},
            {"class", r.cls},
            {"line", r.line},
            {"column", r.column},
            {"fate", fate_name(r.fate)},
            {"detail", r.detail},
            {"killed_by", r.killed_by},
            {"stage", r.stage},
            {"signal", r.signal},
            {"write", r.write},
            {"runs", r.runs},
            {"analyse_seconds", r.analyse_seconds},
            {"sim_seconds", r.sim_seconds},
            {"seconds", r.seconds},
            {"proof", r.proof}};
}

Result result_from_json(const json& j) {
    try {
        Result r;
        r.name = j.at("name").get<std::string>();
        r.file = j.at("file").get<std::string>();
        r.entity = j.at("entity").get<std::string>();
        r.cls = j.at("class").get<std::string>();
        r.line = j.at("line").get<int>();
        r.column = j.at("column").get<int>();
        const std::string fate = j.at("fate").get<std::string>();
        const std::optional<Fate> f = fate_from_name(fate);
        if (!f) throw InputError("bad mutant result: unknown verdict '" + fate + "'");
        r.fate = *f;
        r.detail = j.at("detail").get<std::string>();
        r.killed_by = j.at("killed_by").get<std::string>();
        r.stage = j.at("stage").get<std::string>();
        r.signal = j.at("signal").get<std::string>();
        r.write = j.at("write").get<long>();
        r.runs = j.at("runs").get<int>();
        r.analyse_seconds = j.at("analyse_seconds").get<double>();
        r.sim_seconds = j.at("sim_seconds").get<double>();
        r.seconds = j.at("seconds").get<double>();
        json p = j.at("proof");
        if (!p.contains("assumptions")) p["assumptions"] = json::array();   // absent: no assumptions
        r.proof = p.get<Proof>();
        return r;
    } catch (const json::exception& e) {
        throw InputError(std::string("bad mutant result: ") + e.what());
    }
}

bool synthesise(const std::string& entity, const fs::path& gate_rtl, const fs::path& work, const std::string& side,
                Proof& p) {
    const std::vector<std::string> gens = proof_generics(cosim::rtl_dir() / (entity + ".vhd"));
    std::vector<std::string> argv = {"ghdl", "--synth", "--std=08", "--workdir=" + (work / side).string()};
    fs::create_directories(work / side);
    argv.insert(argv.end(), gens.begin(), gens.end());
    argv.push_back("--out=verilog");
    for (const auto& f : cosim::rtl_sources(gate_rtl)) argv.push_back(f.string());
    argv.insert(argv.end(), {"-e", entity});
    std::string shown;
    for (const auto& a : argv) {
        std::string s = a;
        if (s.rfind(cosim::rtl_dir().string(), 0) == 0) s = "rtl/" + fs::path(s).filename().string();
        if (!gate_rtl.empty() && s.rfind(gate_rtl.string(), 0) == 0) s = "mutant-rtl/" + fs::path(s).filename().string();
        if (s.rfind("--workdir=", 0) == 0) s = "--workdir=" + side;
        shown += (shown.empty() ? "" : " ") + s;
    }
    p.synth += shown + " | " + cosim::kSizedBitLiteralsFilter + " > " + side + ".v\n";
    const fs::path log = work / (side + "-synth.log");
    if (cosim::synth_verilog(argv, work / (side + ".v"), {.log = log}) != 0) {
        p.output = "ghdl --synth of the " + side + " failed: " + util::log_tail(log, 1500);
        return false;
    }
    return true;
}

bool synthesise_pair(const Mutant& m, const fs::path& work, Proof& p) {
    p.entity = proof_entity(m.file);
    fs::create_directories(work);
    const FileEdit edit = edit_of(m);
    const fs::path gate_rtl = mutated_copy(&edit, work);
    return synthesise(p.entity, {}, work, "gold", p) && synthesise(p.entity, gate_rtl, work, "gate", p);
}

std::string load_pair_script(const Mutant& m) {
    const std::string e = proof_entity(m.file);
    return load_script(e, m.file == e + ".vhd" && e == "harris_top");
}

bool run_yosys(const std::string& method, const std::string& script, const fs::path& work, int timeout_s, Proof& p) {
    const fs::path ys = work / (method + ".ys");
    const fs::path log = work / (method + ".log");
    util::write_file_atomic(ys, script);
    fs::remove(log);
    const int rc = util::run_process({"timeout", std::to_string(timeout_s), "yosys", "-q", "-s", ys.filename().string()},
                                     {.cwd = work, .log = log});
    p.method = method;
    p.script = script;
    p.output = util::log_tail(log, 2500);
    if (rc == 124) p.output += fmt::format("\n(yosys stopped after the {} s limit)", timeout_s);
    return rc == 0;
}

Proof prove(const Mutant& m, const fs::path& work, int timeout_s) {
    const auto t0 = Clock::now();
    Proof p;
    if (!synthesise_pair(m, work, p)) {
        p.seconds = since(t0);
        return p;
    }
    const std::string load = load_pair_script(m);
    const std::string equiv_steps = "equiv_make gold gate equiv\nhierarchy -top equiv\nequiv_simple -seq 5\n"
                                    "equiv_induct -seq 5\nequiv_status -assert\n";
    const std::string equiv = load + equiv_steps;
    // the same with GHDL's names of combinational nets (n<k>_o) hidden: equiv_make then pairs
    // only ports, signals and registers, so a mutated comparison's own output, which differs
    // without changing any register, is no longer a goal of its own
    const std::string equiv_named = load + "rename -hide w:n*_o\n" + equiv_steps;
    // registers start at zero on both sides; every input (the reset too) is free in every step
    const std::string miter = load + "miter -equiv -flatten gold gate miter\nhierarchy -top miter\n"
                                     "sat -verify -tempinduct -prove trigger 0 -set-init-zero -seq 1 -maxsteps 40 miter\n";
    for (const auto& [method, script] : {std::pair{std::string("equiv"), equiv}, std::pair{std::string("equiv-named"), equiv_named},
                                         std::pair{std::string("miter"), miter}}) {
        if (run_yosys(method, script, work, timeout_s, p)) {
            p.equivalent = true;
            break;
        }
    }
    p.seconds = since(t0);
    return p;
}

namespace {

/// run_mutant in the scratch directory `work`.
Result run_mutant_in(const Mutant& m, const Options& o, const fs::path& work) {
    const auto t0 = Clock::now();
    Result r;
    r.name = m.name();
    r.file = m.file;
    r.entity = stem(m.file);
    r.cls = class_name(m.cls);
    r.line = m.line;
    r.column = m.column;
    std::vector<const Stimulus*> stimuli = {&o.quick};
    for (const auto& s : o.longer) stimuli.push_back(&s);
    const FileEdit edit = edit_of(m);
    // stimulus after stimulus, up to the first that kills the mutant
    const MutatedRun run = run_mutated(&edit, work, [&](const MutatedRun& so_far) -> std::optional<cosim::GhdlRun> {
        const std::size_t k = so_far.streams.size();
        if (k > 0) {
            if (!kill_reason(so_far.streams.back()).empty()) return std::nullopt;
            say(o, r.name + ": passes " + stimuli[k - 1]->name);
        }
        if (k == stimuli.size()) return std::nullopt;
        const frames::LoadedFrames& lf = frames_of(*stimuli[k]);
        cosim::GhdlRun g;
        g.frames = lf.frames;
        g.frame_names = lf.names;
        g.idle_every = stimuli[k]->idle_every;
        return g;
    });
    r.analyse_seconds = run.analyse_seconds;
    if (!run.analysed) {
        r.fate = Fate::stillborn;
        r.detail = "does not analyse: " + first_error(run.analyse_log);
        r.seconds = since(t0);
        return r;
    }
    r.runs = static_cast<int>(run.streams.size());
    for (const auto& s : run.streams) r.sim_seconds += s.seconds;
    const StreamOutcome& last = run.streams.back();
    if (!last.result && failed_in_elaboration(last.log)) {
        r.fate = Fate::stillborn;
        r.detail = "does not elaborate: " + first_error(last.log);
        r.seconds = since(t0);
        return r;
    }
    if (const std::string reason = kill_reason(last); !reason.empty()) {
        if (last.result && last.result->summary.first_mismatch) {
            const cosim::FirstMismatch& f = *last.result->summary.first_mismatch;
            r.stage = f.stage;
            r.signal = f.signal;
            r.write = f.write;
        }
        r.fate = Fate::killed;
        r.detail = reason;
        r.killed_by = stimuli[run.streams.size() - 1]->name;
        r.seconds = since(t0);
        return r;
    }
    r.fate = Fate::surviving;
    if (o.prove) {
        say(o, r.name + ": survives every stimulus, proving ...");
        r.proof = prove(m, work / "proof", o.proof_timeout_s);
        if (r.proof.equivalent) r.fate = Fate::equivalent;
        else if (has_assumptions(m.file)) {
            say(o, r.name + ": no proof of the entity alone, proving under proven assumptions ...");
            r.proof = prove_assuming(m, work / "proof-assuming", o.proof_timeout_s);
            if (r.proof.equivalent) r.fate = Fate::equivalent_assuming;
        }
        if (r.proof.equivalent) r.proof.reading = verilog_reading();
    }
    r.seconds = since(t0);
    return r;
}

/// `text` with every occurrence of `dir` replaced by `name`.
std::string replace_path(std::string text, const std::string& dir, const std::string& name) {
    for (std::size_t at = text.find(dir); at != std::string::npos; at = text.find(dir, at + name.size()))
        text.replace(at, dir.size(), name);
    return text;
}

}  // namespace

Result run_mutant(const Mutant& m, const Options& o) {
    util::ScratchDir scratch("harris-mutant");
    Result r = run_mutant_in(m, o, scratch.path());
    // the tools' messages name files in the scratch directory, which is gone afterwards and
    // differs on every run: the results (and the reports made from them) call it <scratch>
    r.detail = replace_path(r.detail, scratch.path().string(), "<scratch>");
    r.proof.output = replace_path(r.proof.output, scratch.path().string(), "<scratch>");
    return r;
}

void check_unmutated(const Options& o) {
    util::ScratchDir scratch("harris-mutant-control");
    const frames::LoadedFrames& lf = frames_of(o.quick);
    cosim::GhdlRun g;
    g.frames = lf.frames;
    g.frame_names = lf.names;
    g.idle_every = o.quick.idle_every;
    const MutatedRun run = run_mutated(nullptr, scratch.path(), g);
    std::string why;
    if (!run.analysed) why = "does not analyse: " + first_error(run.analyse_log);
    else if (!run.streams.back().result && failed_in_elaboration(run.streams.back().log))
        why = "does not elaborate: " + first_error(run.streams.back().log);
    else why = kill_reason(run.streams.back());
    if (!why.empty())
        throw SimulatorError("the unmutated rtl/ fails the campaign's own run on " + o.quick.name + " (" +
                             replace_path(why, scratch.path().string(), "<scratch>") +
                             "): no mutant's verdict would mean anything, so none is judged");
    say(o, "control: the unmutated rtl/ passes " + o.quick.name);
}

bool stands_as_read(const Result& r) {
    return r.fate == Fate::killed || r.fate == Fate::stillborn ||
           (r.fate == Fate::equivalent && r.proof.reading == verilog_reading());
}

Reuse reuse_verdicts(const std::vector<Result>& old, const std::vector<Mutant>& sel, int jobs, int timeout_s,
                     const std::function<void(const std::string&)>& progress) {
    Reuse u;
    std::vector<std::pair<const Mutant*, bool>> again;   // a mutant, and whether it was proven unconditionally
    // the CSV keeps a name's line breaks (a mutant of an expression over lines) as spaces
    auto one_line = [](std::string s) {
        std::replace(s.begin(), s.end(), '\n', ' ');
        return s;
    };
    std::set<std::string> seen;
    for (const auto& m : sel) {
        const std::string key = one_line(m.name());
        if (!seen.insert(key).second) throw InputError("two mutants are named '" + key + "' on one line: verdicts not reusable");
        const auto it = std::find_if(old.begin(), old.end(), [&](const Result& r) { return one_line(r.name) == key; });
        if (it == old.end()) throw InputError("the reused verdicts have none for '" + m.name() + "'");
        u.results.push_back(*it);
        u.results.back().name = m.name();
        if (stands_as_read(*it)) continue;
        again.emplace_back(&m, it->fate == Fate::equivalent);
        u.reread += again.back().second;
    }
    u.reused = static_cast<int>(sel.size() - again.size());
    if (progress)
        progress(fmt::format("{} verdicts reused, {} proven again under proven assumptions, {} unconditional proofs made "
                             "again under this reading of GHDL's Verilog",
                             u.reused, again.size() - u.reread, u.reread));
    const auto t0 = Clock::now();
    std::atomic<std::size_t> next{0};
    std::mutex lock;
    std::exception_ptr error;
    auto worker = [&] {
        try {
            for (std::size_t k; (k = next++) < again.size();) {
                const auto [mp, unconditional] = again[k];
                const Mutant& m = *mp;
                const auto t = Clock::now();
                util::ScratchDir scratch("harris-mutant-ag");
                Proof p = unconditional ? prove(m, scratch.path() / "unconditional", timeout_s) : Proof{};
                const bool plain = p.equivalent;
                if (!plain) p = prove_assuming(m, scratch.path(), timeout_s);
                if (p.equivalent) p.reading = verilog_reading();
                p.output = replace_path(p.output, scratch.path().string(), "<scratch>");
                const std::lock_guard<std::mutex> g(lock);
                Result& r = *std::find_if(u.results.begin(), u.results.end(), [&](const Result& x) { return x.name == m.name(); });
                r.proof = p;
                r.fate = plain ? Fate::equivalent : p.equivalent ? Fate::equivalent_assuming : Fate::surviving;
                r.seconds = since(t);
                if (progress) progress(fmt::format("{}: {} ({:.1f} s)", m.name(), fate_name(r.fate), r.seconds));
            }
        } catch (...) {
            const std::lock_guard<std::mutex> g(lock);
            error = std::current_exception();
            next = again.size();
        }
    };
    std::vector<std::thread> pool;
    for (int j = 0; j < std::max(1, jobs); ++j) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
    u.wall_seconds = since(t0);
    return u;
}

double Tally::score() const {
    const int left = mutants - stillborn - equivalent - assuming;
    return left > 0 ? static_cast<double>(killed) / left : 1.0;
}

Tally tally(const std::vector<Result>& rs) {
    Tally t;
    for (const auto& r : rs) {
        ++t.mutants;
        t.stillborn += r.fate == Fate::stillborn;
        t.killed += r.fate == Fate::killed;
        t.equivalent += r.fate == Fate::equivalent;
        t.assuming += r.fate == Fate::equivalent_assuming;
        t.surviving += r.fate == Fate::surviving;
        t.seconds += r.seconds;
    }
    return t;
}

std::string proof_file_name(const Result& r) {
    std::string s = fmt::format("{}_{}_{}_{}", stem(r.file), r.line, r.column, r.cls);
    // two mutants of one place and class differ by their edit: a short hash of the name
    return s + "_" + util::hex64(util::fnv1a(r.name)).substr(0, 6) + ".ys";
}

namespace {

std::string md_cell(std::string s) {
    for (auto& c : s)
        if (c == '|' || c == '\n') c = c == '|' ? '/' : ' ';
    return s;
}

std::string name_cell(const std::string& name) {
    // file:line:column class `a` -> `b`: the edit already in backticks
    return md_cell(name);
}

void tally_row(std::ostringstream& md, const std::string& label, const Tally& t) {
    md << fmt::format("| {} | {} | {} | {} | {} | {} | {} | {:.1f} % | {:.1f} |\n", label, t.mutants, t.stillborn, t.killed,
                      t.equivalent, t.assuming, t.surviving, 100.0 * t.score(), t.mutants ? t.seconds / t.mutants : 0.0);
}

std::string stimulus_text(const Stimulus& s) {
    std::string f;
    if (!s.source.pattern.empty()) f = fmt::format("`{}` {} x {} frame(s)", s.source.pattern, s.source.size, s.source.frames);
    else if (!s.source.pairs.empty())
        f = fmt::format("KITTI {} pairs {} (L R L R ...) cropped to {}", s.source.sequence, s.source.pairs, s.source.size);
    if (s.source.seed != 1) f += fmt::format(", seed {}", s.source.seed);
    if (s.idle_every) f += fmt::format(", an idle cycle every {} writes", s.idle_every);
    return f;
}

/// The report's head: the run that made it, the method and the score with its times.
void markdown_head(std::ostringstream& md, const std::vector<Result>& rs, const ReportInfo& info, const Tally& all) {
    md << "# Mutation campaign: generated mutants\n\n"
       << "Made by `" << info.command << "`" << (info.runner.empty() ? "" : " (" + info.runner + ")")
       << "; every figure below comes from that run" << (info.reused.empty() ? "" : ", with the reused verdicts it names")
       << ".\n\n";
    if (!info.reused.empty()) md << info.reused << "\n\n";
    if (all.mutants < info.generated)
        md << fmt::format("**PARTIAL: {} of the {} generated mutants have a verdict.** The others were not run (a "
                          "selection) or had not finished when this report was rendered; every count below is over "
                          "those with a verdict.\n\n",
                          all.mutants, info.generated);
    md << "The generator (`mutation/vhdl_mutants.hpp`, a tokenizer over `rtl/`) makes " << info.generated
       << " single-point mutants of 10 classes, each named ``file:line:column class `original` -> `replacement` ``.\n"
          "Each is applied to a scratch copy of `rtl/`, analysed with GHDL (mcode) and co-simulated against the\n"
          "unmutated cycle model (`cosim::run_ghdl`: every register compared after reset, after every rising edge\n"
          "and, for any change, while the clock is low; docs/cosim.md), stimulus after\n"
          "stimulus, stopping at the first failure:\n\n";
    md << "1. quick: " << stimulus_text(info.quick) << "\n";
    for (size_t k = 0; k < info.longer.size(); ++k) md << k + 2 << ". " << stimulus_text(info.longer[k]) << "\n";
    md << "\n*Stillborn*: the mutant does not analyse or elaborate (not counted as killed). *Killed*: a stimulus\n"
          "fails (a mismatch, a metavalue, or the simulator stops). A mutant that passes every stimulus is\n"
          "handed to a solver: GHDL synthesises the entity holding the mutation (a package mutant: `harris_top`)\n"
          "from the original and the mutated `rtl/` to Verilog (`ghdl --synth --out=verilog`, the geometry\n"
          "generics at their minimum; a mutant of `harris_top.vhd` itself: its instances, the same on both sides,\n"
          "cut out by `expose -evert` so that their inputs are compared as outputs and their outputs are shared\n"
          "inputs; every other mutant: flattened), and yosys proves the two equal: first `equiv_make` + `equiv_simple -seq 5`\n"
          "+ `equiv_induct -seq 5` + `equiv_status -assert`; if that fails, the same after `rename -hide w:n*_o`\n"
          "(*equiv-named*: GHDL's combinational net names hidden, so that only ports, signals and registers are paired);\n"
          "if that fails, a miter (`miter -equiv -flatten`) and\n"
          "`sat -tempinduct -prove trigger 0` (registers zero in step 1, every input, the reset too, free in every\n"
          "step, outputs compared from step 2 on, induction up to 40 steps). *Proven equivalent* is that solver's verdict and\n"
          "nothing else. A mutant of `harris_response.vhd` or `threshold.vhd` whose proofs fail is proven once more\n"
          "under assumptions on its entity's inputs, each first proven on the netlist of the stage driving them\n"
          "(docs/assume-guarantee.md); *proven equivalent under assumptions*\n"
          "is that proof's verdict, a verdict of its own, with the assumptions it took. A mutant whose proofs all\n"
          "fail is *surviving*, listed below with the last proof's output.\n"
          "GHDL 2.0's Verilog output can mistranslate signed right shifts; gold and gate go through the same\n"
          "translation, so a proof is about the two netlists as GHDL writes them.\n\n"
          "Mutation score = killed / (mutants - stillborn - proven equivalent - proven equivalent under assumptions).\n\n";
    md << fmt::format("**Score: {:.1f} %** ({} killed of {}; {} stillborn, {} proven equivalent, {} proven equivalent under "
                      "assumptions, {} surviving). ",
                      100.0 * all.score(), all.killed, all.mutants - all.stillborn - all.equivalent - all.assuming,
                      all.stillborn, all.equivalent, all.assuming, all.surviving);
    auto mean = [&](auto field) {
        double s = 0;
        for (const auto& r : rs) s += field(r);
        return all.mutants ? s / all.mutants : 0.0;
    };
    if (info.reused.empty()) {
        md << fmt::format("Time per mutant (wall time inside its shard, shards running side by side): {:.1f} s mean ({:.1f} s "
                          "analysis, {:.1f} s co-simulation, {:.2f} co-simulations per mutant; proofs in the rest)",
                          mean([](const Result& r) { return r.seconds; }), mean([](const Result& r) { return r.analyse_seconds; }),
                          mean([](const Result& r) { return r.sim_seconds; }),
                          mean([](const Result& r) { return static_cast<double>(r.runs); }));
        if (info.wall_seconds > 0) md << fmt::format("; the run took {:.0f} s of wall time", info.wall_seconds);
    } else {
        // the verdict list keeps a mutant's time, not its split into analysis and co-simulation
        md << fmt::format("Time per mutant: {:.1f} s mean, {:.2f} co-simulations per mutant (a reused verdict's time is "
                          "that of the run that made it; a proof run again here, its own)",
                          mean([](const Result& r) { return r.seconds; }),
                          mean([](const Result& r) { return static_cast<double>(r.runs); }));
    }
    md << ".\n\n";

}

/// The tallies per class and per entity, and which stimulus killed how many.
void markdown_tallies(std::ostringstream& md, const std::vector<Result>& rs, const ReportInfo& info, const Tally& all) {
    const std::string head =
        "| mutants | stillborn | killed | proven equivalent | proven under assumptions | surviving | score | s per mutant |\n";
    md << "## Per class\n\n| class " << head << "|---|---|---|---|---|---|---|---|---|\n";
    for (auto c : all_classes()) {
        std::vector<Result> g;
        for (const auto& r : rs)
            if (r.cls == class_name(c)) g.push_back(r);
        if (!g.empty()) tally_row(md, class_name(c), tally(g));
    }
    tally_row(md, "**all**", all);
    md << "\n## Per entity\n\n| entity (file) " << head << "|---|---|---|---|---|---|---|---|---|\n";
    std::vector<std::string> order;
    for (const auto& r : rs)
        if (std::find(order.begin(), order.end(), r.file) == order.end()) order.push_back(r.file);
    for (const auto& f : order) {
        std::vector<Result> g;
        for (const auto& r : rs)
            if (r.file == f) g.push_back(r);
        tally_row(md, stem(f) + " (`" + f + "`)", tally(g));
    }
    tally_row(md, "**all**", all);

    md << "\n## Killed by\n\n| stimulus | mutants killed |\n|---|---|\n";
    std::vector<std::string> names = {info.quick.name};
    for (const auto& s : info.longer) names.push_back(s.name);
    for (const auto& n : names) {
        const auto k = std::count_if(rs.begin(), rs.end(), [&](const Result& r) { return r.killed_by == n; });
        md << "| " << n << " | " << k << " |\n";
    }

}

/// The surviving, proven equivalent (with and without assumptions) and stillborn mutants.
void markdown_verdict_lists(std::ostringstream& md, const std::vector<Result>& rs, const ReportInfo& info) {
    md << "\n## Surviving mutants\n\n";
    bool any = false;
    for (const auto& r : rs) {
        if (r.fate != Fate::surviving) continue;
        any = true;
        md << "### " << name_cell(r.name) << "\n\nPasses every stimulus. Proof of `" << r.proof.entity << "` ("
           << (r.proof.method.empty() ? "no proof ran" : r.proof.method) << ") fails:\n\n```\n"
           << r.proof.synth << r.proof.script << "```\n\n```\n" << r.proof.output << "\n```\n\n";
    }
    if (!any) md << "None.\n\n";

    md << "## Proven equivalent\n\nEach script is in `" << info.proofs_dir
       << "/`, with the GHDL commands that make its `gold.v` and `gate.v` as comments.\n\n";
    any = false;
    for (const auto& r : rs) {
        if (r.fate != Fate::equivalent) continue;
        if (!any) md << "| mutant | entity proven | method | script |\n|---|---|---|---|\n";
        any = true;
        md << "| " << name_cell(r.name) << " | " << r.proof.entity << " | " << r.proof.method << " | `"
           << proof_file_name(r) << "` |\n";
    }
    if (!any) md << "None.\n";

    md << "\n## Proven equivalent under assumptions\n\n"
          "Each proof assumes the properties listed, every one proven first on the netlist of the stage that drives\n"
          "the entity's inputs (a proof whose guarantee fails is refused); the script is in `"
       << info.proofs_dir << "/`, and so is each guarantee's (`guarantee_<k>_<entity>.ys`).\n\n";
    any = false;
    for (const auto& r : rs) {
        if (r.fate != Fate::equivalent_assuming) continue;
        if (!any) md << "| mutant | entity proven | assumptions (each proven) | script |\n|---|---|---|---|\n";
        any = true;
        std::string a;
        for (const auto& x : r.proof.assumptions) a += (a.empty() ? "" : "; ") + x;
        md << "| " << name_cell(r.name) << " | " << r.proof.entity << " | " << md_cell(a) << " | `" << proof_file_name(r)
           << "` |\n";
    }
    if (!any) md << "None.\n";

    md << "\n## Stillborn mutants\n\n";
    any = false;
    for (const auto& r : rs) {
        if (r.fate != Fate::stillborn) continue;
        if (!any) md << "| mutant | why |\n|---|---|\n";
        any = true;
        md << "| " << name_cell(r.name) << " | " << md_cell(r.detail) << " |\n";
    }
    if (!any) md << "None.\n";
}

}  // namespace

std::string markdown(const std::vector<Result>& rs, const ReportInfo& info) {
    std::ostringstream md;
    const Tally all = tally(rs);
    markdown_head(md, rs, info, all);
    markdown_tallies(md, rs, info, all);
    markdown_verdict_lists(md, rs, info);
    md << "\nEvery mutant's verdict is in `docs/mutation-campaign.csv`. The hand-written mutants, the fast smoke\n"
          "set CI runs, are in `docs/mutation-smoke.md`.\n";
    return md.str();
}

std::string verilog_reading() { return util::hex64(util::fnv1a(cosim::kVerilogReading)); }

std::string rtl_hash() {
    std::uint64_t h = util::fnv1a("");
    for (const auto& p : cosim::rtl_sources()) h = util::fnv1a(p.filename().string() + "\n" + util::read_file(p), h);
    return util::hex64(h);
}

namespace {
constexpr const char* csv_header =
    "name,file,line,column,class,entity,fate,detail,killed_by,stage,signal,write,runs,seconds,proof_method,assumptions,"
    "rtl_hash,verilog_reading";
/// The header of a list written before the column verilog_reading.
const std::string csv_header_unread = std::string(csv_header).substr(0, std::string(csv_header).rfind(','));

/// The fields of one CSV line (quoted fields with "" for a quote; no line breaks inside).
std::vector<std::string> csv_fields(const std::string& line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
            else if (c == '"') quoted = false;
            else out.back() += c;
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            out.emplace_back();
        } else {
            out.back() += c;
        }
    }
    return out;
}
}  // namespace

std::string csv(const std::vector<Result>& rs, const std::string& rtl) {
    auto q = [](std::string s) {
        std::string o = "\"";
        for (char c : s) {
            if (c == '"') o += '"';
            o += c == '\n' ? ' ' : c;
        }
        return o + "\"";
    };
    std::ostringstream out;
    out << csv_header << '\n';
    for (const auto& r : rs) {
        std::string a;
        for (const auto& x : r.proof.assumptions) a += (a.empty() ? "" : ";") + x;
        out << q(r.name) << ',' << r.file << ',' << r.line << ',' << r.column << ',' << r.cls << ',' << r.entity << ','
            << fate_name(r.fate) << ',' << q(r.detail) << ',' << r.killed_by << ',' << r.stage << ',' << q(r.signal) << ','
            << r.write << ',' << r.runs << ',' << fmt::format("{:.2f}", r.seconds) << ',' << r.proof.method << ','
            << q(a) << ',' << rtl << ',' << r.proof.reading << '\n';
    }
    return out.str();
}

std::vector<Result> results_from_csv(const std::string& text, const std::string& source, const std::string& rtl) {
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line) || (line != csv_header && line != csv_header_unread))
        throw InputError(source + ": not a verdict list of `mutate --generate` (its first line must be: " + csv_header + ")");
    const std::size_t fields = line == csv_header ? 18 : 17;
    std::vector<Result> rs;
    for (int n = 2; std::getline(in, line); ++n) {
        const auto f = csv_fields(line);
        const std::string at = fmt::format("{} line {}", source, n);
        if (f.size() != fields) throw InputError(at + fmt::format(": {} fields, not {}", f.size(), fields));
        if (f[16] != rtl)
            throw InputError(at + ": a verdict about RTL of hash " + f[16] + ", not about rtl/ as it is (" + rtl +
                             "): verdicts about other RTL are not reused");
        Result r;
        try {
            r.name = f[0], r.file = f[1], r.line = std::stoi(f[2]), r.column = std::stoi(f[3]), r.cls = f[4];
            r.entity = f[5], r.detail = f[7], r.killed_by = f[8], r.stage = f[9], r.signal = f[10];
            r.write = std::stol(f[11]), r.runs = std::stoi(f[12]), r.seconds = std::stod(f[13]);
        } catch (const std::exception&) {
            throw InputError(at + ": a number field is not a number");
        }
        const std::optional<Fate> fate = fate_from_name(f[6]);
        if (!fate) throw InputError(at + ": unknown verdict '" + f[6] + "'");
        r.fate = *fate;
        r.proof.method = f[14];
        if (fields == 18) r.proof.reading = f[17];
        r.proof.equivalent = r.fate == Fate::equivalent || r.fate == Fate::equivalent_assuming;
        if (!r.proof.method.empty()) r.proof.entity = proof_entity(r.file);
        for (std::size_t a = 0, b; a < f[15].size(); a = b + 1) {
            b = f[15].find(';', a);
            if (b == std::string::npos) b = f[15].size();
            r.proof.assumptions.push_back(f[15].substr(a, b - a));
        }
        rs.push_back(std::move(r));
    }
    return rs;
}

namespace {

/// The proven mutants' scripts, runnable from a folder holding the gold.v and gate.v the
/// commands in their first lines write.
void write_proofs(const std::vector<Result>& rs, const fs::path& dir) {
    for (const auto& r : rs) {
        // a reused verdict has no script here: its file from the run that proved it stays
        if ((r.fate != Fate::equivalent && r.fate != Fate::equivalent_assuming) || r.proof.script.empty()) continue;
        std::string s = "# " + r.name + ": proven equivalent by yosys (" + r.proof.method + ")\n";
        for (const auto& a : r.proof.assumptions) s += "# assuming (proven first): " + a + "\n";
        s += "# gold.v and gate.v (mutant-rtl/: rtl/ with the mutant applied):\n";
        std::string line;
        for (char c : r.proof.synth) {
            if (c == '\n') {
                s += "#   " + line + "\n";
                line.clear();
            } else {
                line += c;
            }
        }
        util::write_file_atomic(dir / proof_file_name(r), s + r.proof.script);
    }
    // the guarantees the proofs under assumptions assume, each a script of its own
    if (std::any_of(rs.begin(), rs.end(), [](const Result& r) { return r.fate == Fate::equivalent_assuming; }))
        for (const auto& [name, text] : guarantee_files()) util::write_file_atomic(dir / name, text);
}

}  // namespace

void write_report_files(const std::filesystem::path& md, const std::vector<Result>& rs, ReportInfo info) {
    info.proofs_dir = (md.parent_path().filename() / "mutation-proofs").string();
    write_proofs(rs, md.parent_path() / "mutation-proofs");
    util::write_file_atomic(std::filesystem::path(md).replace_extension(".csv"), csv(rs, rtl_hash()));
    util::write_file_atomic(md, markdown(rs, info));
}

std::string reuse_note(const Reuse& u, const std::string& csv_file, int jobs) {
    const auto& rs = u.results;
    return fmt::format(
        "**Verdicts reused.** {} of these {} verdicts (every killed and stillborn one, and every unconditionally proven "
        "one made under this reading of GHDL's Verilog) are read from `{}`, the verdict list of an earlier complete run "
        "of this campaign, reused because its rtl_hash equals that of rtl/ as it is (a hash over every rtl/ file's name "
        "and text): the same mutants of the same RTL, co-simulated against the same cycle model. {} unconditionally "
        "proven there under another (or an unrecorded) reading of GHDL's Verilog were proven again by this command, "
        "unconditionally where that holds, else under proven assumptions. The other {} (surviving or proven under "
        "assumptions there: they passed every stimulus and their unconditional proofs failed on this RTL) were proven "
        "again under proven assumptions. {} at a time, in {:.0f} s of wall time.",
        u.reused, rs.size(), csv_file, u.reread, rs.size() - u.reused - u.reread, jobs, u.wall_seconds);
}

}  // namespace hc::mutation
