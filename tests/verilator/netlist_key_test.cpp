// netlist_key_test.cpp: the netlist cache key (and so the gate's pass marker, keyed on the
// gate's netlist keys) covers every field of the formats: no two configurations share one.
#include <catch2/catch.hpp>

#include <set>

#include "cosim/verilator/netlist.hpp"

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
