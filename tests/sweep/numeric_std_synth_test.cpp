// GHDL's simulation of numeric_std against GHDL's synthesis of it (through yosys and z3), one
// construct of rtl/*.vhd at a time (tests/sweep/numeric_std_probe.vhd): where the netlist is
// not the VHDL, the netlist route of the derived ranges proves something about GHDL's
// synthesis only. GHDL, yosys and z3 on PATH (label netlist).
#include <catch2/catch.hpp>

#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "model/util/util.hpp"
#include "sweep/ranges.hpp"

using namespace hc;
using namespace hc::sweep;
namespace fs = std::filesystem;

namespace {

/// An output of numeric_std_probe: its width and how its bits read as an integer.
struct Output {
    const char* name;
    int width;
    enum Kind { is_signed, is_unsigned, is_bit } kind;
};
const std::vector<Output> kOutputs = {
    {"shrink", 4, Output::is_signed},        {"slice_shrink", 4, Output::is_signed}, {"extend", 12, Output::is_signed},
    {"slice_extend", 8, Output::is_signed},  {"u_extend", 12, Output::is_unsigned},  {"neg", 9, Output::is_signed},
    {"prod", 16, Output::is_signed},         {"sum", 8, Output::is_signed},          {"diff", 8, Output::is_signed},
    {"gt", 1, Output::is_bit},               {"ge", 1, Output::is_bit},              {"shr", 8, Output::is_signed}};

using Values = std::map<std::string, std::int64_t>;

const fs::path kProbe = fs::path(HC_SOURCE_DIR) / "tests/sweep/numeric_std_probe.vhd";
const fs::path kBench = fs::path(HC_SOURCE_DIR) / "tests/sweep/numeric_std_probe_tb.vhd";

/// The probe analysed for simulation and synthesised to SMT-LIB, in a scratch directory.
struct Probe {
    util::ScratchDir dir{"numeric-std-probe"};
    std::string netlist;

    Probe() {
        const fs::path log = dir.path() / "log";
        REQUIRE(util::run_process({"ghdl", "-a", "--std=08", kProbe.string(), kBench.string()}, {.cwd = dir.path(), .log = log}) == 0);
        REQUIRE(util::run_process({"ghdl", "--synth", "--std=08", "--out=verilog", kProbe.string(), "-e", "numeric_std_probe"},
                                  {.cwd = dir.path(), .log = log, .stdout_file = dir.path() / "probe.v"}) == 0);
        REQUIRE(util::run_process({"yosys", "-q", "-p",
                                   "read_verilog probe.v; hierarchy -top numeric_std_probe; proc; opt; write_smt2 -wires probe.smt2"},
                                  {.cwd = dir.path(), .log = log}) == 0);
        netlist = util::read_file(dir.path() / "probe.smt2");
    }

    /// GHDL's simulation: numeric_std_probe_tb's "name=value" lines.
    Values simulated(int x, int y, int u) const {
        const fs::path out = dir.path() / "sim.txt";
        REQUIRE(util::run_process({"ghdl", "--elab-run", "--std=08", "numeric_std_probe_tb", fmt::format("-gX={}", x),
                                   fmt::format("-gY={}", y), fmt::format("-gU={}", u)},
                                  {.cwd = dir.path(), .log = dir.path() / "sim.log", .stdout_file = out}) == 0);
        Values v;
        const std::string text = util::read_file(out) + util::read_file(dir.path() / "sim.log");
        for (const Output& o : kOutputs) {
            const std::string key = fmt::format("(report note): {}=", o.name);
            const size_t at = text.rfind(key);
            REQUIRE(at != std::string::npos);
            v[o.name] = std::stoll(text.substr(at + key.size()));
        }
        return v;
    }

    /// GHDL's synthesis read by yosys: the netlist's outputs at the inputs, by z3.
    Values synthesised(int x, int y, int u) const {
        std::string q = netlist + "(declare-fun s () |numeric_std_probe_s|)\n";
        const auto in = [&](const char* name, int v) {
            q += fmt::format("(assert (= (|numeric_std_probe_n {}| s) (_ bv{} 8)))\n", name, v & 0xff);
        };
        in("x", x);
        in("y", y);
        in("u", u);
        std::vector<std::string> get;
        for (const Output& o : kOutputs) {
            const std::string w = fmt::format("(|numeric_std_probe_n {}| s)", o.name);
            const std::string as64 = o.kind == Output::is_bit      ? fmt::format("(ite {} (_ bv1 64) (_ bv0 64))", w)
                                     : o.kind == Output::is_signed ? fmt::format("((_ sign_extend {}) {})", 64 - o.width, w)
                                                                   : fmt::format("((_ zero_extend {}) {})", 64 - o.width, w);
            q += fmt::format("(define-fun o_{} () (_ BitVec 64) {})\n", o.name, as64);
            get.push_back(fmt::format("o_{}", o.name));
        }
        const Z3Answer a = run_z3(q, 10'000'000, get);
        REQUIRE(a.sat == Sat::sat);
        Values v;
        for (const Output& o : kOutputs) v[o.name] = a.values.at(fmt::format("o_{}", o.name));
        return v;
    }
};

}  // namespace

TEST_CASE("GHDL's synthesis drops the sign bit of a signed resize to fewer bits, and shifts a signed value right logically",
          "[netlist][sweep][numeric_std]") {
    const Probe p;
    // resize(to_signed(88, 8), 4): numeric_std keeps the sign bit (0) and the low 3 bits (000): 0;
    // the netlist takes x[3:0] = 1000: -8
    const Values sim88 = p.simulated(88, 3, 200), net88 = p.synthesised(88, 3, 200);
    CHECK(sim88.at("shrink") == 0);
    CHECK(net88.at("shrink") == -8);
    // resize(x(7 downto 1), 4) at 88: the slice is 44 = 0101100; numeric_std: 0 & 100 = 4; netlist 1100 = -4
    CHECK(sim88.at("slice_shrink") == 4);
    CHECK(net88.at("slice_shrink") == -4);
    // shift_right(to_signed(-128, 8), 2): numeric_std shifts the sign in (-32); the netlist's
    // Verilog `$signed(x) >> 2` is a logical shift (00100000 = 32)
    const Values sim128 = p.simulated(-128, 3, 200), net128 = p.synthesised(-128, 3, 200);
    CHECK(sim128.at("shr") == -32);
    CHECK(net128.at("shr") == 32);

    // the shrinks differ exactly where the netlist's top bit (bit 3 of the value, bit 4 of x
    // for the slice) is not the sign bit numeric_std keeps, the shift exactly where x < 0;
    // every other construct agrees everywhere it is tried
    const std::vector<std::array<int, 3>> inputs = {{5, -128, 0}, {-3, 127, 255}, {88, 3, 200}, {-128, 3, 200},
                                                    {127, -1, 1}, {-1, -1, 128},  {0, 0, 0},    {-100, 90, 17}};
    for (const auto& [x, y, u] : inputs) {
        const Values sim = p.simulated(x, y, u), net = p.synthesised(x, y, u);
        for (const Output& o : kOutputs) {
            INFO(fmt::format("{} at x={} y={} u={}: simulation {}, netlist {}", o.name, x, y, u, sim.at(o.name), net.at(o.name)));
            const std::string n = o.name;
            const auto bit = [x = x](int k) { return (x >> k) & 1; };
            if ((n == "shrink" && bit(3) != bit(7)) || (n == "slice_shrink" && bit(4) != bit(7)) || (n == "shr" && x < 0))
                CHECK(sim.at(n) != net.at(n));
            else
                CHECK(sim.at(n) == net.at(n));
        }
    }
}
