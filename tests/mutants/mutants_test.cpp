// mutants_test: generated mutants with known verdicts: one the quick stimulus kills, one
// that does not analyse (stillborn), one that passes every stimulus and yosys proves
// equivalent; the selection flags and the job kind's manifest.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

#include <algorithm>

#include "jobs/jobs.hpp"
#include "mutants/mutants.hpp"

using namespace hc;

namespace {

const mutation::Mutant& by_name(const std::vector<mutation::Mutant>& all, const std::string& name) {
    for (const auto& m : all)
        if (m.name() == name) return m;
    FAIL("no generated mutant " << name);
    return all.front();
}

mutants::Options quick_only() {
    mutants::Options o;
    o.prove = false;
    return o;
}

}  // namespace

TEST_CASE("a product turned into a sum is killed by the quick stimulus in m_products", "[mutants]") {
    const auto all = mutants::generate_all();
    const auto r = mutants::run_mutant(by_name(all, "m_products.vhd:33:23 arith `*` -> `+`"), quick_only());
    CHECK(r.fate == "killed");
    CHECK(r.killed_by == mutants::quick_stimulus().name);
    CHECK(r.stage == "m_products");
    CHECK(r.runs == 1);
}

TEST_CASE("a mutant GHDL cannot analyse is stillborn, not killed", "[mutants]") {
    const auto all = mutants::generate_all();
    // `i > 1 or i <= 5 and load = '0'`: VHDL does not mix `and` and `or` without parentheses
    const auto r = mutants::run_mutant(by_name(all, "input_converter_mux.vhd:72:28 logic `and` -> `or`"), quick_only());
    CHECK(r.fate == "stillborn");
    CHECK(r.detail.rfind("does not analyse: ", 0) == 0);
    CHECK(r.runs == 0);
}

TEST_CASE("a mutant GHDL cannot elaborate is stillborn, not killed", "[mutants]") {
    const auto all = mutants::generate_all();
    // a(0, 1): a static index below the window's range
    const auto r = mutants::run_mutant(by_name(all, "sobel_x.vhd:30:27 literal `1` -> `0`"), quick_only());
    CHECK(r.fate == "stillborn");
    CHECK(r.detail.rfind("does not elaborate: ", 0) == 0);
    CHECK(r.runs == 1);
}

TEST_CASE("a mutant no stimulus kills is proven equivalent by yosys", "[mutants]") {
    const auto all = mutants::generate_all();
    mutants::Options o;
    o.longer = mutants::long_stimuli({});
    // resize(a(2, 1), PIXEL_W + 1): an unsigned pixel fits, and so does its negation in the
    // wider difference
    const auto r = mutants::run_mutant(by_name(all, "sobel_x.vhd:31:34 resize `PIXEL_W + 2` -> `(PIXEL_W + 2) - 1`"), o);
    CHECK(r.fate == "equivalent");
    CHECK(r.runs == 1 + static_cast<int>(o.longer.size()));
    CHECK(r.proof.equivalent);
    CHECK(r.proof.entity == "sobel_x");
    // the internal nets differ in width, so the first equiv_make pairs nets that differ; with
    // GHDL's net names hidden only ports and registers are paired, and they are proven equal
    CHECK(r.proof.method == "equiv-named");
    CHECK(r.proof.script.find("rename -hide w:n*_o\nequiv_make gold gate equiv") != std::string::npos);
}

TEST_CASE("a selection takes classes, files and name prefixes, and refuses unknown ones", "[mutants]") {
    const auto all = mutants::generate_all();
    const auto cls = mutants::select(all, {{}, {"stuck"}, {}});
    CHECK(!cls.empty());
    for (const auto& m : cls) CHECK(m.cls == mutation::MutantClass::stuck);
    const auto file = mutants::select(all, {{}, {}, {"m_products.vhd"}});
    CHECK(file.size() == 43);
    const auto at = mutants::select(all, {{"m_products.vhd:46:21 "}, {}, {}});
    CHECK(at.size() == 2);
    CHECK_THROWS_AS(mutants::select(all, {{}, {"swap"}, {}}), InputError);
    CHECK_THROWS_AS(mutants::select(all, {{}, {}, {"nosuch.vhd"}}), InputError);
    CHECK_THROWS_AS(mutants::select(all, {{"nosuch.vhd:1:1"}, {}, {}}), InputError);
}

TEST_CASE("the mutants job splits the named mutants into shards in order", "[mutants]") {
    jobs::MutantsJob j;
    for (int i = 0; i < 10; ++i) j.names.push_back("m" + std::to_string(i));
    j.per_shard = 4;
    const cluster::Manifest m = jobs::mutants_manifest(j);
    CHECK(m.job == "mutants");
    REQUIRE(m.shards.size() == 3);
    CHECK(m.shards[0]["names"].size() == 4);
    CHECK(m.shards[2]["names"].back() == "m9");
    const auto kinds = jobs::registry().names();
    CHECK(std::find(kinds.begin(), kinds.end(), "mutants") != kinds.end());
}
