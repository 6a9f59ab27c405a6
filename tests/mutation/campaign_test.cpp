// campaign_test: generated mutants with known verdicts: one the quick stimulus kills, one
// that does not analyse and one that does not elaborate (stillborn), one that passes every
// stimulus and yosys proves equivalent; the selection flags and the job kind's manifest.
#include <catch2/catch.hpp>

#include <algorithm>

#include "io/frames/frames.hpp"
#include "model/driver/host_driver.hpp"
#include "model/harris/find_max.hpp"
#include "model/harris/harris_top.hpp"
#include "mutation/mutate_generated_job.hpp"
#include "mutation/mutation.hpp"
#include "tools/registry.hpp"

using namespace hc;

namespace {

const mutation::Mutant& by_name(const std::vector<mutation::Mutant>& all, const std::string& name) {
    for (const auto& m : all)
        if (m.name() == name) return m;
    FAIL("no generated mutant " << name);
    return all.front();
}

mutation::Options quick_only() {
    mutation::Options o;
    o.prove = false;
    return o;
}

}  // namespace

TEST_CASE("a product turned into a sum is killed by the quick stimulus in m_products", "[mutants]") {
    const auto all = mutation::generate_all();
    const auto r = mutation::run_mutant(by_name(all, "m_products.vhd:33:23 arith `*` -> `+`"), quick_only());
    CHECK(r.fate == mutation::Fate::killed);
    CHECK(r.killed_by == mutation::quick_stimulus().name);
    CHECK(r.stage == "m_products");
    CHECK(r.runs == 1);
}

TEST_CASE("a mutant GHDL cannot analyse or elaborate is stillborn, not killed", "[mutants]") {
    struct Stillborn {
        const char* mutant;
        const char* detail;   ///< how its detail starts
        int runs;             ///< the runs its result counts
    };
    const Stillborn c = GENERATE(values<Stillborn>({
        // `i > 1 or i <= 5 and load = '0'`: VHDL does not mix `and` and `or` without parentheses
        {"input_converter_mux.vhd:72:28 logic `and` -> `or`", "does not analyse: ", 0},
        // a(0, 1): a static index below the window's range
        {"sobel_x.vhd:30:27 literal `1` -> `0`", "does not elaborate: ", 1},
    }));
    INFO(c.mutant);
    const auto all = mutation::generate_all();
    const auto r = mutation::run_mutant(by_name(all, c.mutant), quick_only());
    CHECK(r.fate == mutation::Fate::stillborn);
    CHECK(r.detail.rfind(c.detail, 0) == 0);
    CHECK(r.runs == c.runs);
}

TEST_CASE("a mutant no stimulus kills is proven equivalent by yosys", "[mutants]") {
    const auto all = mutation::generate_all();
    mutation::Options o;
    o.longer = mutation::long_stimuli({});
    // resize(a(2, 1), PIXEL_W + 1): an unsigned pixel fits, and so does its negation in the
    // wider difference
    const auto r = mutation::run_mutant(by_name(all, "sobel_x.vhd:31:34 resize `PIXEL_W + 2` -> `(PIXEL_W + 2) - 1`"), o);
    CHECK(r.fate == mutation::Fate::equivalent);
    CHECK(r.runs == 1 + static_cast<int>(o.longer.size()));
    CHECK(r.proof.equivalent);
    CHECK(r.proof.entity == "sobel_x");
    // the internal nets differ in width, so the first equiv_make pairs nets that differ; with
    // GHDL's net names hidden only ports and registers are paired, and they are proven equal
    CHECK(r.proof.method == "equiv-named");
    CHECK(r.proof.script.find("rename -hide w:n*_o\nequiv_make gold gate equiv") != std::string::npos);
}

TEST_CASE("a selection takes classes, files and name prefixes, and refuses unknown ones", "[mutants]") {
    const auto all = mutation::generate_all();
    const auto cls = mutation::select(all, {{}, {"stuck"}, {}});
    CHECK(!cls.empty());
    for (const auto& m : cls) CHECK(m.cls == mutation::MutantClass::stuck);
    const auto file = mutation::select(all, {{}, {}, {"m_products.vhd"}});
    CHECK(file.size() == 43);
    const auto at = mutation::select(all, {{"m_products.vhd:46:21 "}, {}, {}});
    CHECK(at.size() == 2);
    CHECK_THROWS_AS(mutation::select(all, {{}, {"swap"}, {}}), InputError);
    CHECK_THROWS_AS(mutation::select(all, {{}, {}, {"nosuch.vhd"}}), InputError);
    CHECK_THROWS_AS(mutation::select(all, {{"nosuch.vhd:1:1"}, {}, {}}), InputError);
}

TEST_CASE("each verdict has one name, in the JSON and the CSV, read back as the same verdict", "[mutants]") {
    const std::vector<std::pair<mutation::Fate, std::string>> expected = {
        {mutation::Fate::stillborn, "stillborn"},
        {mutation::Fate::killed, "killed"},
        {mutation::Fate::equivalent, "equivalent"},
        {mutation::Fate::equivalent_assuming, "equivalent-assuming"},
        {mutation::Fate::surviving, "surviving"}};
    REQUIRE(mutation::fate_names.size() == expected.size());
    for (const auto& [fate, name] : expected) {
        CHECK(mutation::fate_name(fate) == name);
        CHECK(mutation::fate_from_name(name) == fate);
        mutation::Result r;
        r.name = "x.vhd:1:1 literal `0` -> `1`";
        r.fate = fate;
        const nlohmann::json j = mutation::to_json(r);
        CHECK(j.at("fate") == name);
        CHECK(mutation::result_from_json(j).fate == fate);
        const std::string line = mutation::csv({r}, "abc");
        CHECK(line.find("," + name + ",") != std::string::npos);
        CHECK(mutation::results_from_csv(line, "t.csv", "abc").at(0).fate == fate);
    }
    CHECK_FALSE(mutation::fate_from_name("Killed"));
    CHECK_FALSE(mutation::fate_from_name("equivalent_assuming"));
    nlohmann::json bad = mutation::to_json(mutation::Result{});
    bad["fate"] = "proven";
    CHECK_THROWS_AS(mutation::result_from_json(bad), InputError);
}

TEST_CASE("a verdict's proof has one key a field, only its assumptions may be absent", "[mutants]") {
    mutation::Result r;
    r.proof.assumptions = {"one: [0, 1]"};
    r.proof.method = "assume-guarantee";
    nlohmann::json j = mutation::to_json(r);
    std::vector<std::string> keys;
    for (auto it = j.at("proof").begin(); it != j.at("proof").end(); ++it) keys.push_back(it.key());
    CHECK(keys == std::vector<std::string>{"assumptions", "entity", "equivalent", "method", "output", "reading", "script",
                                           "seconds", "synth"});
    CHECK(mutation::result_from_json(j).proof.assumptions == r.proof.assumptions);
    j["proof"].erase("assumptions");
    CHECK(mutation::result_from_json(j).proof.assumptions.empty());
    CHECK(mutation::result_from_json(j).proof.method == "assume-guarantee");
    j["proof"].erase("method");
    CHECK_THROWS_AS(mutation::result_from_json(j), InputError);
}

TEST_CASE("the mutants job splits the named mutants into shards in order", "[mutants]") {
    mutation::MutantsJob j;
    for (int i = 0; i < 10; ++i) j.names.push_back("m" + std::to_string(i));
    j.per_shard = 4;
    const cluster::Manifest m = mutation::mutants_manifest(j);
    CHECK(m.job == "mutate-generated");
    REQUIRE(m.shards.size() == 3);
    CHECK(m.shards[0]["names"].size() == 4);
    CHECK(m.shards[2]["names"].back() == "m9");
    const auto kinds = tools::registry().names();
    CHECK(std::find(kinds.begin(), kinds.end(), "mutate-generated") != kinds.end());
}

/// The frames of the longer stimulus `name` (without the data directory's streams).
frames::LoadedFrames longer_stream(const std::string& name) {
    const auto longer = mutation::long_stimuli({});
    const auto it = std::find_if(longer.begin(), longer.end(), [&](const mutation::Stimulus& s) { return s.name == name; });
    if (it == longer.end()) FAIL("no longer stimulus named " << name);
    return frames::load_frames(it->source);
}

TEST_CASE("a longer stimulus holds a response exactly at the threshold then in force", "[mutants]") {
    // threshold.vhd keeps a response r >= thr: only a response equal to a nonzero threshold
    // tells >= from >, and the stream chosen for it must hold one in the cycle model
    const auto loaded = longer_stream("blocks_33x21x3_seed18");
    const Geometry g{loaded.frames.front().width, loaded.frames.front().height};
    HostDriver driver(g, frames::pointers(loaded.frames));
    HarrisTop model(g, Formats{});
    BusEvent ev;
    long at_threshold = 0;   // writes after which a thresholded response equals the threshold
    while (driver.next(ev)) {
        model.write(ev.data);
        const auto o = model.observe();
        const std::int64_t thr = o.thr.value();
        bool equal = false;
        for (const auto& row : o.tr)
            for (const auto& r : row) equal = equal || (thr != 0 && r.value() == thr);
        at_threshold += equal ? 1 : 0;
    }
    CHECK(at_threshold >= 1);
}

TEST_CASE("a longer stimulus publishes another maximum when find-max takes a neighbour of the window centre",
          "[mutants]") {
    // harris_top feeds find_max the centre hrm(2, 2) on steps with t(4) set; fed hrm(2, 1) or
    // hrm(2, 3) instead, the period maxima must differ somewhere in the stream chosen for it
    const auto loaded = longer_stream("random_40x30x3_idle13");
    const Geometry g{loaded.frames.front().width, loaded.frames.front().height};
    HostDriver driver(g, frames::pointers(loaded.frames));
    HarrisTop model(g, Formats{});
    FindMax fed[3] = {FindMax(Formats{}), FindMax(Formats{}), FindMax(Formats{})};   // hrm(2, 1..3)
    bool differs[3] = {false, false, false};
    BusEvent ev;
    while (driver.next(ev)) {
        const auto before = model.observe();   // find_max samples its inputs at the edge
        model.write(ev.data);
        if ((before.t >> 4) & 1)
            for (int j = 0; j < 3; ++j) fed[j] = fed[j].next(before.hr[1][j], g);
        REQUIRE(fed[1].max.value() == model.find_max().max.value());   // the centre is the model's own
        for (int j = 0; j < 3; ++j) differs[j] = differs[j] || fed[j].max.value() != fed[1].max.value();
    }
    CHECK(differs[0]);
    CHECK(differs[2]);
}
