// assume_guarantee_test: the ranges harris_response's proofs assume, proven on the upstream
// stages' netlists; a claimed range tighter than the netlist gives is refused, and so is every
// proof that would assume it; survivors of the entity-level proofs proven under the proven
// ranges (harris_response) and under the proven enable (threshold); verdict lists reused only
// for the RTL they are about.
#include <catch2/catch.hpp>

#include <map>

#include "cosim/ghdl_verilog.hpp"
#include "mutation/mutation.hpp"
#include "model/util/util.hpp"

using namespace hc;

namespace {

/// The generated mutant of this name (select takes name prefixes; the full name is unique).
mutation::Mutant named(const std::string& name) {
    const auto v = mutation::select(mutation::generate_all(), {{name}, {}, {}});
    REQUIRE(v.size() == 1);
    return v.front();
}

constexpr int timeout_s = 600;

}  // namespace

TEST_CASE("the interval ranges of the thesis formats", "[assume-guarantee]") {
    const mutation::StageRanges r = mutation::derive_ranges();
    CHECK(r.sobel.lo == -1020);
    CHECK(r.sobel.hi == 1020);
    CHECK(r.m_square.lo == 0);
    CHECK(r.m_square.hi == 1020 * 1020 / 32);                // 32512
    CHECK(r.m_cross.lo == -32513);                           // floor(-1040400 / 32)
    CHECK(r.m_cross.hi == 32512);
    CHECK(r.bf_square.lo == 0);
    CHECK(r.bf_square.hi == 9 * 32512 / 16);                 // 18288
    CHECK(r.bf_cross.lo == -18289);                          // floor(-292617 / 16)
    CHECK(r.bf_cross.hi == 18288);
    Formats narrow;
    narrow.m_prod_w = 20;                                    // 1020^2 needs 21 signed bits
    CHECK_THROWS_AS(mutation::derive_ranges(narrow), InputError);
}

TEST_CASE("every guarantee is proven on its stage's netlist", "[assume-guarantee]") {
    util::ScratchDir work("ag-test");
    auto gs = mutation::response_guarantees(mutation::derive_ranges());
    gs.push_back(mutation::enable_guarantee());
    REQUIRE(gs.size() == 6);
    for (std::size_t k = 0; k < gs.size(); ++k) {
        INFO(gs[k].name);
        const mutation::Proof p = mutation::prove_guarantee(gs[k], work.path() / std::to_string(k), timeout_s);
        CHECK(p.equivalent);
        CHECK(p.entity == gs[k].entity);
    }
    // the scripts the report's folder gets: the same proofs, with the GHDL command as a comment
    const auto files = mutation::guarantee_files();
    REQUIRE(files.size() == gs.size());
    for (std::size_t k = 0; k < gs.size(); ++k) {
        CHECK(files[k].first == "guarantee_" + std::to_string(k + 1) + "_" + gs[k].entity + ".ys");
        const std::string script = mutation::guarantee_script(gs[k]);
        CHECK(files[k].second.substr(files[k].second.size() - script.size()) == script);
        // GHDL's Verilog through the bit-string rewrite every reader of it uses (cosim/ghdl_verilog.hpp)
        CHECK(files[k].second.find("-e " + gs[k].entity + " | " + cosim::kSizedBitLiteralsFilter + " > " + gs[k].entity + ".v") !=
              std::string::npos);
    }
}

TEST_CASE("a range tighter than the netlist gives is refused and so is the proof assuming it", "[assume-guarantee]") {
    util::ScratchDir work("ag-test");
    const auto m = named("harris_response.vhd:51:24 resize `RESP_W` -> `RESP_W - 1`");
    SECTION("M's a and c claimed one below their maximum") {
        mutation::StageRanges r = mutation::derive_ranges();
        r.m_square.hi -= 1;                                  // 1020^2 / 32 = 32512 is reached (ix = 1020)
        const auto gs = mutation::response_guarantees(r);
        CHECK_FALSE(mutation::prove_guarantee(gs[2], work.path() / "g", timeout_s).equivalent);
        const mutation::Proof p = mutation::prove_assuming(m, work.path() / "p", timeout_s, r);
        CHECK_FALSE(p.equivalent);
        CHECK(p.method == "assume-guarantee");
        CHECK(p.output.rfind("guarantee not proven, so no proof assumes it: m_products:", 0) == 0);
        CHECK(p.assumptions.size() == 2);                    // the two Sobel ranges held, nothing after them
        CHECK_FALSE(std::filesystem::exists(work.path() / "p" / "assume-guarantee.ys"));
    }
    SECTION("the block sums of b claimed non-negative") {
        mutation::StageRanges r = mutation::derive_ranges();
        r.bf_cross.lo = 0;
        const mutation::Proof p = mutation::prove_assuming(m, work.path() / "p", timeout_s, r);
        CHECK_FALSE(p.equivalent);
        CHECK(p.output.rfind("guarantee not proven, so no proof assumes it: block_filter: the sum of nine b", 0) == 0);
    }
}

TEST_CASE("a survivor of harris_response is proven equivalent under the proven ranges", "[assume-guarantee]") {
    util::ScratchDir work("ag-test");
    // resize(ac, RESP_W - 1): equal while a*c fits 31 bits, which a, c in [0, 18288] give
    const auto m = named("harris_response.vhd:51:24 resize `RESP_W` -> `RESP_W - 1`");
    REQUIRE(mutation::has_assumptions(m.file));
    const mutation::Proof p = mutation::prove_assuming(m, work.path(), timeout_s);
    INFO(p.output);
    CHECK(p.equivalent);
    CHECK(p.method == "assume-guarantee");
    CHECK(p.entity == "harris_response");
    CHECK(p.assumptions.size() == 5);
    CHECK(p.script.find("assume(in_a >= 0 && in_a <= 18288)") != std::string::npos);
    CHECK(p.script.find("-prove m.gold.ac[31:29] 0") != std::string::npos);
}

TEST_CASE("a weakened upstream guarantee (a and c anywhere in 16 signed bits) and the proof of 51:24 fails at a real overflow",
          "[assume-guarantee]") {
    util::ScratchDir work("ag-test");
    const auto m = named("harris_response.vhd:51:24 resize `RESP_W` -> `RESP_W - 1`");
    // the block sums of a and c claimed only to fit their 16 bits: true (the guarantee is still
    // proven), but weaker than [0, 18288], so resize(ac, RESP_W - 1) can now drop a bit
    mutation::StageRanges r = mutation::derive_ranges();
    r.bf_square = {-32768, 32767};
    const mutation::Proof p = mutation::prove_assuming(m, work.path() / "p", timeout_s, r);
    INFO(p.output);
    CHECK_FALSE(p.equivalent);
    CHECK(p.method == "assume-guarantee");
    CHECK(p.assumptions.size() == 5);   // every guarantee, the weakened one too, is proven: only the downstream proof fails
    CHECK(p.script.find("assume(in_a >= -32768 && in_a <= 32767)") != std::string::npos);
    // the solver's failing input: a*c outside the 31 signed bits the mutant keeps (the only
    // place it differs), with a or c outside the true range [0, 18288]
    const std::vector<mutation::CexValue> cex = mutation::counterexample(p, work.path() / "p");
    REQUIRE_FALSE(cex.empty());
    const long long lo = -(1LL << 30), hi = (1LL << 30) - 1;
    bool overflow = false;
    for (int step = 1; step <= 12; ++step) {
        std::map<std::string, long long> in;
        for (const auto& x : cex)
            if (x.step == step) in[x.signal] = x.value;
        if (!in.count("in_a") || !in.count("in_b") || !in.count("in_c")) continue;
        const long long a = in["in_a"], c = in["in_c"];
        INFO("step " << step << ": a = " << a << ", b = " << in["in_b"] << ", c = " << c);
        if (a * c < lo || a * c > hi) {
            overflow = true;
            CHECK((a < 0 || c < 0 || a > 18288 || c > 18288));   // unreachable under the true guarantee
        }
    }
    CHECK(overflow);
}

TEST_CASE("threshold's reset value of r0_delay is proven unobservable under the proven enable", "[assume-guarantee]") {
    util::ScratchDir work("ag-test");
    const auto m = named("threshold.vhd:37:29 literal `0` -> `1`");
    const mutation::Proof entity_alone = mutation::prove(m, work.path() / "alone", 120);
    CHECK_FALSE(entity_alone.equivalent);                    // en free: the first write after reset shows r0_delay
    const mutation::Proof p = mutation::prove_assuming(m, work.path() / "assuming", timeout_s);
    INFO(p.output);
    CHECK(p.equivalent);
    CHECK(p.assumptions == std::vector<std::string>{mutation::enable_guarantee().name});
}

TEST_CASE("a verdict list is reused only for the RTL it is about", "[assume-guarantee]") {
    mutation::Result k;
    k.name = "x.vhd:1:2 literal `0` -> `1`";
    k.file = "threshold.vhd";
    k.entity = "threshold";
    k.cls = "literal";
    k.fate = mutation::Fate::equivalent_assuming;
    k.detail = "a \"quoted\", comma";
    k.proof.method = "assume-guarantee";
    k.proof.assumptions = {"one: [0, 1]", "two"};
    const std::string text = mutation::csv({k}, "abc");
    const auto back = mutation::results_from_csv(text, "t.csv", "abc");
    REQUIRE(back.size() == 1);
    CHECK(back[0].name == k.name);
    CHECK(back[0].fate == k.fate);
    CHECK(back[0].detail == k.detail);
    CHECK(back[0].proof.assumptions == k.proof.assumptions);
    CHECK(back[0].proof.entity == "threshold");
    CHECK_THROWS_WITH(mutation::results_from_csv(text, "t.csv", "abd"), Catch::Contains("not about rtl/ as it is"));
    CHECK_THROWS_AS(mutation::results_from_csv("name,file\n", "t.csv", "abc"), InputError);
}

TEST_CASE("an unconditional proof is reused only under the reading of GHDL's Verilog it was made under",
          "[assume-guarantee]") {
    mutation::Result e;
    e.name = "x.vhd:1:2 literal `0` -> `1`";
    e.file = "threshold.vhd";
    e.fate = mutation::Fate::equivalent;
    e.proof.method = "equiv";
    e.proof.reading = mutation::verilog_reading();
    const std::string text = mutation::csv({e}, "abc");
    CHECK(text.substr(0, text.find('\n')).ends_with(",rtl_hash,verilog_reading"));
    const auto back = mutation::results_from_csv(text, "t.csv", "abc");
    REQUIRE(back.size() == 1);
    CHECK(back[0].proof.reading == mutation::verilog_reading());
    CHECK(mutation::stands_as_read(back[0]));
    // a list written before the column: its proofs' reading is unknown, so they are made again
    const std::string header = text.substr(0, text.find('\n'));
    std::string line = text.substr(text.find('\n') + 1);
    line = line.substr(0, line.rfind(','));
    const auto old = mutation::results_from_csv(header.substr(0, header.rfind(',')) + "\n" + line + "\n", "old.csv", "abc");
    REQUIRE(old.size() == 1);
    CHECK(old[0].proof.reading.empty());
    CHECK_FALSE(mutation::stands_as_read(old[0]));
    mutation::Result other = back[0];
    other.proof.reading = "0123456789abcdef";
    CHECK_FALSE(mutation::stands_as_read(other));
    mutation::Result killed = back[0];
    killed.fate = mutation::Fate::killed;
    killed.proof = {};
    CHECK(mutation::stands_as_read(killed));
    mutation::Result assuming = back[0];
    assuming.fate = mutation::Fate::equivalent_assuming;
    CHECK_FALSE(mutation::stands_as_read(assuming));
    // a line of the other width than its header is refused
    CHECK_THROWS_WITH(mutation::results_from_csv(header + "\n" + line + "\n", "t.csv", "abc"), Catch::Contains("17 fields, not 18"));
}
