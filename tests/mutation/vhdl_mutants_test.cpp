// vhdl_mutants_test: the mutant generator on a small hand-written design, every mutant
// checked, and on the project's rtl/ (deterministic, every mutant applies and changes text).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "mutation/mutation.hpp"

using namespace hc::mutation;

namespace {

const std::string kDesign = R"(-- a counter with an enable; comments are never mutated: a + b < 3
library ieee;
use ieee.numeric_std.all;
entity cnt is
  generic (W : positive := 4);
  port (clk, rst, en : in std_logic; q : out unsigned(W - 1 downto 0));
end entity cnt;
architecture rtl of cnt is
  signal c : unsigned(W - 1 downto 0);
begin
  step : process (clk, rst) is
  begin
    if rst = '0' then
      c <= to_unsigned(0, W);
    elsif clk'event and clk = '1' then
      if en = '1' then
        c <= c + 2;
      end if;
    end if;
  end process step;
  q <= c(W - 1 downto 1) & '0' when c < 9 else resize(c, W);
end architecture rtl;
)";

std::set<std::string> names(const std::vector<Mutant>& v) {
    std::set<std::string> s;
    for (const auto& m : v) s.insert(m.name());
    return s;
}

}  // namespace

TEST_CASE("every mutant of a small design is the expected single edit", "[mutation]") {
    const auto v = generate_mutants("cnt.vhd", kDesign);
    const std::set<std::string> expected = {
        "cnt.vhd:13:8 negate `rst = '0'` -> `not (rst = '0')`",
        "cnt.vhd:13:12 rel `=` -> `/=`",
        "cnt.vhd:14:24 literal `0` -> `1`",
        "cnt.vhd:15:11 negate `clk'event and clk = '1'` -> `not (clk'event and clk = '1')`",
        "cnt.vhd:15:21 logic `and` -> `or`",
        "cnt.vhd:15:29 rel `=` -> `/=`",
        "cnt.vhd:16:10 negate `en = '1'` -> `not (en = '1')`",
        "cnt.vhd:16:10 enable `en = '1'` -> `true`",
        "cnt.vhd:16:13 rel `=` -> `/=`",
        "cnt.vhd:17:14 stuck `c + 2` -> `to_unsigned(0, W)`",
        "cnt.vhd:17:16 arith `+` -> `-`",
        "cnt.vhd:17:18 literal `2` -> `3`",
        "cnt.vhd:17:18 literal `2` -> `1`",
        "cnt.vhd:21:10 slice `W - 1` -> `(W - 1) + 1`",
        "cnt.vhd:21:10 slice `W - 1` -> `(W - 1) - 1`",
        "cnt.vhd:21:12 arith `-` -> `+`",
        "cnt.vhd:21:14 literal `1` -> `2`",
        "cnt.vhd:21:14 literal `1` -> `0`",
        "cnt.vhd:21:23 literal `1` -> `2`",
        "cnt.vhd:21:23 literal `1` -> `0`",
        "cnt.vhd:21:37 negate `c < 9` -> `not (c < 9)`",
        "cnt.vhd:21:39 rel `<` -> `<=`",
        "cnt.vhd:21:41 literal `9` -> `10`",
        "cnt.vhd:21:41 literal `9` -> `8`",
        "cnt.vhd:21:58 resize `W` -> `W - 1`",
    };
    CHECK(names(v) == expected);
    CHECK(v.size() == expected.size());
}

TEST_CASE("a mutant applies to its own text only and changes exactly its range", "[mutation]") {
    const auto v = generate_mutants("cnt.vhd", kDesign);
    for (const auto& m : v) {
        const std::string r = m.apply(kDesign);
        CHECK(r.substr(0, m.offset) == kDesign.substr(0, m.offset));
        CHECK(r.substr(m.offset, m.replacement.size()) == m.replacement);
        CHECK(r.substr(m.offset + m.replacement.size()) == kDesign.substr(m.offset + m.length));
    }
    CHECK_THROWS_AS(v.front().apply("entity x is end;"), std::invalid_argument);
}

TEST_CASE("the observation port's code is not mutated", "[mutation]") {
    const std::string d = R"(architecture rtl of t is
begin
  observed : if OBSERVE generate
    obs <= a + b;
  end generate observed;
  z <= a + b;
end architecture rtl;
)";
    const auto v = generate_mutants("t.vhd", d);
    REQUIRE(v.size() == 1);
    CHECK(v[0].name() == "t.vhd:6:10 arith `+` -> `-`");
}

TEST_CASE("the project's RTL gives the same mutants every time, each a real edit", "[mutation]") {
    const std::filesystem::path rtl = std::filesystem::path(HC_SOURCE_DIR) / "rtl";
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(rtl))
        if (e.path().extension() == ".vhd") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    REQUIRE(!files.empty());
    std::size_t total = 0;
    std::set<std::string> seen;
    for (const auto& f : files) {
        std::ifstream in(f);
        std::stringstream ss;
        ss << in.rdbuf();
        const auto a = generate_mutants(f.filename().string(), ss.str());
        const auto b = generate_mutants(f.filename().string(), ss.str());
        REQUIRE(names(a) == names(b));
        for (const auto& m : a) {
            CHECK(m.apply(ss.str()) != ss.str());
            CHECK(seen.insert(m.name()).second);
        }
        total += a.size();
    }
    // several hundred single-point mutants (the count is printed for the report)
    CHECK(total >= 300);
    WARN("generated mutants of rtl/: " << total);
}

TEST_CASE("the campaign reports quote the command they are given", "[mutation]") {
    hc::mutation::Result killed;
    killed.name = "sobel_x.vhd:30:5:arith";
    killed.file = "sobel_x.vhd";
    killed.entity = "sobel_x";
    killed.cls = "arith";
    killed.fate = hc::mutation::Fate::killed;
    killed.detail = "mismatch";
    hc::mutation::ReportInfo info;
    info.command = "harris-cosim mutate --generate --class arith --only 'sobel_x.vhd:30:'";
    info.runner = "local runner, 2 jobs, 1 shards";
    info.generated = 1;
    const std::string md = hc::mutation::markdown({killed}, info);
    CHECK(md.find("Made by `" + info.command + "` (local runner, 2 jobs, 1 shards)") != std::string::npos);
    // the hand-written list's report too
    const hc::mutation::SmokeList list = hc::mutation::load_smoke_list(HC_SOURCE_DIR "/mutation/mutations.json");
    const std::string typed = "harris-cosim mutate --only sobel_x_sign --report 'out/smoke report.md'";
    CHECK(hc::mutation::smoke_markdown(list, {}, "mutation/mutations.json", typed)
              .find("Made by `" + typed + "` (mutations: `mutation/mutations.json`)") != std::string::npos);
}
