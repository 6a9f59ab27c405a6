// netlist_key_test.cpp: the netlist cache key (and so the gate's pass marker, keyed on the
// gate's netlist keys) covers every field of the formats: no two configurations share one.
// And the trust a verilate run states of itself.
#include <catch2/catch.hpp>

#include <set>

#include "cosim/cosim.hpp"
#include "cosim/verilator/gate.hpp"
#include "cosim/verilator/netlist.hpp"
#include "cosim/verilator/verilate.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;
using namespace hc;

TEST_CASE("changing any one field of the formats changes the netlist cache key", "[model][verilator]") {
    const Geometry g{16, 12};
    const std::string base = vl::config_key({g, Formats{}, true, {}});
    std::set<std::string> keys{base};
    for (const auto& fld : format_fields()) {
        Formats f;
        f.*(fld.member) += 1;
        INFO(fld.name);
        const std::string k = vl::config_key({g, f, true, {}});
        CHECK(k != base);
        keys.insert(k);
    }
    CHECK(keys.size() == 1 + format_fields().size());
}

TEST_CASE("the netlist cache key names the size and the observation variant", "[model][verilator]") {
    const std::string k = vl::config_key({Geometry{1241, 376}, Formats{}, false, {}});
    CHECK(k.starts_with("1241x376_f"));
    CHECK(k.find("_noobs_") != std::string::npos);
    CHECK(vl::config_key({Geometry{1241, 376}, Formats{}, true, {}}).find("_obs_") != std::string::npos);
}

TEST_CASE("the gate's verdict key changes when an RTL source's contents change, never only its path", "[model][verilator]") {
    // a scratch copy of m_products.vhd substituted for rtl/'s (netlist.hpp: variants)
    util::ScratchDir scratch("hc-gate-key");
    const fs::path copy = scratch.path() / "m_products.vhd";
    const std::string text = util::read_file(cosim::rtl_dir() / "m_products.vhd");
    util::write_file_atomic(copy, text);
    const std::string original = vl::gate_key(Formats{}, {copy});
    CHECK(original == vl::gate_key(Formats{}, {copy}));
    util::write_file_atomic(copy, text + "-- one more line\n");
    CHECK(vl::gate_key(Formats{}, {copy}) != original);
    Formats f;
    f.m_drop += 1;
    util::write_file_atomic(copy, text);
    CHECK(vl::gate_key(f, {copy}) != original);
}

TEST_CASE("the gate's netlists are built unoptimised and keyed apart from the optimised ones", "[model][verilator]") {
    vl::NetlistConfig c{Geometry{10, 10}, Formats{}, true, {}};
    const std::string optimised = vl::config_key(c);
    c.optimise = false;
    CHECK(vl::config_key(c).find("_obs_O0_") != std::string::npos);
    CHECK(optimised.find("_O0") == std::string::npos);
}

TEST_CASE("verilate states its own trust: samples only at best, failed on any fault, - when nothing ran",
          "[model][verilator]") {
    vl::VerilateResult built;
    built.netlist_key = "k";
    CHECK(std::string(vl::netlist_trust_name(vl::netlist_trust(built))) == "-");
    vl::VerilateResult passed = built;
    passed.gate = vl::GateResult{};
    passed.run = vl::RunResult{};
    CHECK(vl::netlist_trust(passed) == vl::NetlistTrust::samples);
    CHECK(std::string(vl::netlist_trust_name(vl::netlist_trust(passed))) == "samples only");
    vl::VerilateResult ungated = built;   // --no-gate: the lock step alone
    ungated.run = vl::RunResult{};
    CHECK(vl::netlist_trust(ungated) == vl::NetlistTrust::samples);
    vl::VerilateResult mismatched = passed;
    mismatched.run->mismatches = 1;
    CHECK(vl::netlist_trust(mismatched) == vl::NetlistTrust::failed);
    vl::VerilateResult faulted = built;
    faulted.gate = vl::GateResult{vl::GateVerdict::translation_fault};
    CHECK(vl::netlist_trust(faulted) == vl::NetlistTrust::failed);
    CHECK(vl::netlist_trust(true, false, true) == vl::NetlistTrust::stages_proven);
}
