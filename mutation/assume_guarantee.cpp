// assume_guarantee.cpp: proofs of mutants under proven assumptions (see campaign.hpp).
#include <algorithm>
#include <chrono>
#include <sstream>

#include <fmt/format.h>

#include "mutation/campaign.hpp"
#include "cosim/cosim.hpp"
#include "cosim/ghdl_verilog.hpp"
#include "mutation/proof_steps.hpp"
#include "model/util/util.hpp"

namespace hc::mutation {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr int pixel_w = 8;   // rtl/harris_pkg.vhd PIXEL_W: not a generic

/// where prove_assuming's `sat` writes its log with the inputs of a failing base case
constexpr const char* kModelLog = "sat-model.log";

/// floor(x / 2^k)
long long floor_shift(long long x, int k) { return x >> k; }

/// `v` must fit a signed register of `w` bits.
Interval fitting(Interval v, int w, const std::string& what) {
    const long long top = 1LL << (w - 1);
    if (v.lo < -top || v.hi > top - 1)
        throw InputError(fmt::format("{} spans [{}, {}], which does not fit its {} bits: no range to prove", what, v.lo,
                                     v.hi, w));
    return v;
}

std::string range_text(const Interval& v) { return fmt::format("[{}, {}]", v.lo, v.hi); }

/// `x` (a signed Verilog expression) within `v`.
std::string within(const std::string& x, const Interval& v) {
    return fmt::format("({} >= {} && {} <= {})", x, v.lo, x, v.hi);
}

/// The property of harris_response's step-1 register `reg` (PROD_W bits) that a product of
/// factors in `v` has: its bits from the one above the largest product's up to the sign zero.
struct ProductBits {
    int from = 0, to = 0;
};
ProductBits zero_bits(long long largest, int prod_w) {
    int k = 0;
    while (k < 62 && (1LL << k) <= largest) ++k;
    return {k, prod_w - 1};
}

std::string chk_header(const std::string& ports) { return "module chk(" + ports + ");\n"; }

Guarantee sobel_guarantee(const std::string& entity, const std::string& out, int sobel_w, const Interval& v) {
    Guarantee g;
    g.entity = entity;
    g.name = fmt::format("{}: {} in {} for every 8-bit window", entity, out, range_text(v));
    g.checker = chk_header(fmt::format("input clk, input rst, input en, input write, input [{}:0] a, "
                                       "output signed [{}:0] {}",
                                       9 * pixel_w - 1, sobel_w - 1, out)) +
                fmt::format("  {0} u(.clk(clk), .rst(rst), .en(en), .write(write), .a(a), .{1}({1}));\n"
                            "  always @* assert{2};\nendmodule\n",
                            entity, out, within(out, v));
    return g;
}

Guarantee block_guarantee(const std::string& what, const Interval& in, const Interval& out, int in_w, int bf_w,
                          const std::string& assumed) {
    Guarantee g;
    g.entity = "block_filter";
    g.name = fmt::format("block_filter: the sum of nine {} in {} is in {}", what, range_text(in), range_text(out));
    g.assumes = {assumed};
    g.checker = chk_header(fmt::format("input clk, input rst, input en, input write, input [{}:0] a, "
                                       "output signed [{}:0] sum",
                                       9 * in_w - 1, bf_w - 1)) +
                fmt::format("  block_filter u(.clk(clk), .rst(rst), .en(en), .write(write), .a(a), .sum(sum));\n"
                            "  genvar k;\n"
                            "  for (k = 0; k < 9; k = k + 1) begin : window\n"
                            "    always @* assume{};\n"
                            "  end\n"
                            "  always @* assert{};\nendmodule\n",
                            within(fmt::format("$signed(a[{} * k +: {}])", in_w, in_w), in), within("sum", out));
    return g;
}

Proof failed_guarantee(Proof p, const Proof& g, const std::string& name) {
    p.method = "assume-guarantee";
    p.script = g.script;
    p.output = "guarantee not proven, so no proof assumes it: " + name + "\n" + g.synth + g.output;
    return p;
}

}  // namespace

StageRanges derive_ranges(const Formats& f) {
    StageRanges r;
    const long long px = (1LL << pixel_w) - 1;
    // -p11 - 2 p21 - p31 + p13 + 2 p23 + p33
    r.sobel = fitting({-4 * px, 4 * px}, f.sobel_w, "the Sobel gradient");
    const long long s = std::max(-r.sobel.lo, r.sobel.hi);
    const Interval sq = fitting({0, s * s}, f.m_prod_w, "ix*ix before the cut");
    const Interval cross = fitting({-s * s, s * s}, f.m_prod_w, "ix*iy before the cut");
    r.m_square = {floor_shift(sq.lo, f.m_drop), floor_shift(sq.hi, f.m_drop)};
    r.m_cross = {floor_shift(cross.lo, f.m_drop), floor_shift(cross.hi, f.m_drop)};
    const Interval bsq = fitting({9 * r.m_square.lo, 9 * r.m_square.hi}, f.bf_sum_w, "the block sum of a");
    const Interval bcross = fitting({9 * r.m_cross.lo, 9 * r.m_cross.hi}, f.bf_sum_w, "the block sum of b");
    r.bf_square = {floor_shift(bsq.lo, f.bf_drop), floor_shift(bsq.hi, f.bf_drop)};
    r.bf_cross = {floor_shift(bcross.lo, f.bf_drop), floor_shift(bcross.hi, f.bf_drop)};
    return r;
}

std::vector<Guarantee> response_guarantees(const StageRanges& r) {
    const Formats f;
    std::vector<Guarantee> v = {sobel_guarantee("sobel_x", "ix", f.sobel_w, r.sobel),
                                sobel_guarantee("sobel_y", "iy", f.sobel_w, r.sobel)};
    Guarantee m;
    m.entity = "m_products";
    m.name = fmt::format("m_products: a, c in {}, b in {} when ix, iy are in {}", range_text(r.m_square),
                         range_text(r.m_cross), range_text(r.sobel));
    m.assumes = {v[0].name, v[1].name};
    m.checker = chk_header(fmt::format("input clk, input rst, input en, input write, input signed [{0}:0] ix, "
                                       "input signed [{0}:0] iy, output signed [{1}:0] a, output signed [{1}:0] b, "
                                       "output signed [{1}:0] c",
                                       f.sobel_w - 1, f.m_w() - 1)) +
                fmt::format("  m_products u(.clk(clk), .rst(rst), .en(en), .write(write), .ix(ix), .iy(iy), .a(a), "
                            ".b(b), .c(c));\n"
                            "  always @* begin\n    assume{};\n    assume{};\n"
                            "    assert{};\n    assert{};\n    assert{};\n  end\nendmodule\n",
                            within("ix", r.sobel), within("iy", r.sobel), within("a", r.m_square),
                            within("c", r.m_square), within("b", r.m_cross));
    v.push_back(m);
    v.push_back(block_guarantee("a (or c)", r.m_square, r.bf_square, f.m_w(), f.bf_w(), m.name));
    v.push_back(block_guarantee("b", r.m_cross, r.bf_cross, f.m_w(), f.bf_w(), m.name));
    return v;
}

Guarantee enable_guarantee() {
    Guarantee g;
    g.entity = "control_shift_register";
    g.name = "control_shift_register: t = 0 until the first write after a reset";
    // w: a write since the last reset (the reset is asynchronous, active low, as the RTL's)
    g.checker = chk_header("input clk, input rst, input write, input ready, output [5:0] t") +
                "  control_shift_register u(.clk(clk), .write(write), .rst(rst), .ready(ready), .t(t));\n"
                "  reg w;\n"
                "  always @(posedge clk or negedge rst)\n"
                "    if (!rst) w <= 1'b0; else if (write) w <= 1'b1;\n"
                "  always @* assert(t == 6'b000000 || w);\nendmodule\n";
    return g;
}

std::string guarantee_script(const Guarantee& g) {
    return fmt::format("read_verilog {}.v\nread_verilog -formal <<EOT\n{}EOT\nhierarchy -top chk\n"
                       "proc\nflatten\nasync2sync\nopt -fast\n"
                       "sat -verify -tempinduct -prove-asserts -set-assumes -set-init-zero -maxsteps 4\n",
                       g.entity, g.checker);
}

std::vector<std::pair<std::string, std::string>> guarantee_files(const StageRanges& r) {
    auto gs = response_guarantees(r);
    gs.push_back(enable_guarantee());
    std::string sources;
    for (const auto& f : cosim::rtl_sources()) sources += " rtl/" + f.filename().string();
    std::vector<std::pair<std::string, std::string>> out;
    for (std::size_t k = 0; k < gs.size(); ++k) {
        const Guarantee& g = gs[k];
        std::string head = "# guarantee: " + g.name + "\n";
        for (const auto& a : g.assumes) head += "# assuming (a guarantee of its own): " + a + "\n";
        head += fmt::format("# {0}.v:\n#   ghdl --synth --std=08 --workdir={0} --out=verilog{1} -e {0} | {2} > {0}.v\n", g.entity,
                            sources, cosim::kSizedBitLiteralsFilter);
        out.emplace_back(fmt::format("guarantee_{}_{}.ys", k + 1, g.entity), head + guarantee_script(g));
    }
    return out;
}

Proof prove_guarantee(const Guarantee& g, const fs::path& work, int timeout_s) {
    const auto t0 = Clock::now();
    Proof p;
    p.entity = g.entity;
    fs::create_directories(work);
    if (!synthesise(g.entity, {}, work, g.entity, p)) {
        p.seconds = since(t0);
        return p;
    }
    p.equivalent = run_yosys("guarantee", guarantee_script(g), work, timeout_s, p);
    p.seconds = since(t0);
    return p;
}

bool has_assumptions(const std::string& file) { return file == "harris_response.vhd" || file == "threshold.vhd"; }

Proof prove_assuming(const Mutant& m, const fs::path& work, int timeout_s, const StageRanges& r) {
    const auto t0 = Clock::now();
    Proof p;
    p.method = "assume-guarantee";
    p.entity = proof_entity(m.file);
    if (!has_assumptions(m.file)) {
        p.output = "no assumptions are proven for the inputs of " + p.entity;
        return p;
    }
    const std::vector<Guarantee> gs = m.file == "threshold.vhd" ? std::vector<Guarantee>{enable_guarantee()}
                                                                 : response_guarantees(r);
    for (std::size_t k = 0; k < gs.size(); ++k) {
        const Proof g = prove_guarantee(gs[k], work / fmt::format("guarantee{}", k), timeout_s);
        if (!g.equivalent) {
            p = failed_guarantee(p, g, gs[k].name);
            p.seconds = since(t0);
            return p;
        }
        p.assumptions.push_back(gs[k].name);
    }
    if (!synthesise_pair(m, work, p)) {
        p.seconds = since(t0);
        return p;
    }
    const Formats f;
    std::string wrapper, expose, goals;
    if (p.entity == "harris_response") {
        // harris_response's a, b, c are block_filter's sums (harris_top's port map)
        const int bw = f.bf_w() - 1;
        wrapper = fmt::format(
            "module ag(input in_clk, input in_rst, input in_en0, input in_en1, input in_write, input signed [{0}:0] in_a, "
            "input signed [{0}:0] in_b, input signed [{0}:0] in_c, output trigger);\n"
            "  miter m(.in_clk(in_clk), .in_rst(in_rst), .in_en0(in_en0), .in_en1(in_en1), .in_write(in_write), "
            ".in_a(in_a), .in_b(in_b), .in_c(in_c), .trigger(trigger));\n"
            "  always @* begin\n    assume{1};\n    assume{2};\n    assume{3};\n  end\nendmodule\n",
            bw, within("in_a", r.bf_square), within("in_c", r.bf_square), within("in_b", r.bf_cross));
        // invariants of the registers a*c and b*b (their top bits zero) and the k-terms equal
        const long long b2 = std::max(r.bf_cross.lo * r.bf_cross.lo, r.bf_cross.hi * r.bf_cross.hi);
        const ProductBits bb = zero_bits(b2, f.prod_w());
        goals = "-prove trigger 0";
        // a*c's top bits are zero only when a and c are non-negative: otherwise no invariant on ac
        if (r.bf_square.lo >= 0) {
            const ProductBits ac = zero_bits(r.bf_square.hi * r.bf_square.hi, f.prod_w());
            if (ac.from <= ac.to) goals += fmt::format(" -prove m.gold.ac[{}:{}] 0", ac.to, ac.from);
        }
        if (bb.from <= bb.to) goals += fmt::format(" -prove m.gold.bb[{}:{}] 0", bb.to, bb.from);
        goals += " -prove m.gold.ktr2 m.gate.ktr2";
    } else {
        // threshold's en is t(5) of control_shift_register, its rst and write theirs
        // (harris_top's port map): by the guarantee, en is 0 at a write unless a write
        // followed the last reset
        const int rw = f.resp_w - 1;
        expose = "expose miter/w:gold.r0_delay miter/w:gate.r0_delay\n";
        wrapper = fmt::format(
            "module ag(input in_clk, input in_rst, input in_en, input in_write, input [{0}:0] in_r0, input [{0}:0] in_thr, "
            "output trigger);\n"
            "  wire [{0}:0] gold_r0_delay, gate_r0_delay;\n"
            "  miter m(.in_clk(in_clk), .in_rst(in_rst), .in_en(in_en), .in_write(in_write), .in_r0(in_r0), "
            ".in_thr(in_thr), .trigger(trigger), .\\gold.r0_delay (gold_r0_delay), .\\gate.r0_delay (gate_r0_delay));\n"
            "  reg w;\n"
            "  always @(posedge in_clk or negedge in_rst)\n"
            "    if (!in_rst) w <= 1'b0; else if (in_write) w <= 1'b1;\n"
            "  always @* begin\n"
            "    assume(!(in_write && in_en) || w);\n"
            "    assert(gold_r0_delay == gate_r0_delay || !w);\n"
            "  end\nendmodule\n",
            rw);
        goals = "-prove trigger 0 -prove-asserts";
    }
    const std::string script = load_pair_script(m) + "miter -equiv -flatten gold gate miter\n" + expose +
                               "read_verilog -formal <<EOT\n" + wrapper +
                               "EOT\nproc\nhierarchy -top ag\nflatten\nasync2sync\nopt -fast\n"
                               "tee -o " + std::string(kModelLog) + " sat -verify -tempinduct " + goals +
                               " -set-assumes -set-init-zero -seq 1 -maxsteps 10 -show-inputs\n";
    fs::remove(work / kModelLog);
    p.equivalent = run_yosys("assume-guarantee", script, work, timeout_s, p);
    p.seconds = since(t0);
    return p;
}

std::vector<CexValue> counterexample(const Proof& p, const fs::path& work) {
    if (p.method != "assume-guarantee" || p.script.find(kModelLog) == std::string::npos)
        throw std::logic_error("counterexample: the proof did not print its inputs (method " + p.method + ")");
    const fs::path log = work / kModelLog;
    if (!fs::exists(log)) throw std::logic_error("counterexample: the proof's " + log.string() + " is missing");
    // "SAT temporal induction proof finished - model found for base case: FAIL!", then the
    // table: "  <step> \\<signal> <dec> <hex> <bin>"
    const std::string out = util::read_file(log);
    const size_t found = out.find("model found for base case: FAIL!");
    std::vector<CexValue> v;
    if (found == std::string::npos) return v;
    std::istringstream in(out.substr(found));
    for (std::string line; std::getline(in, line);) {
        std::istringstream w(line);
        std::string step, name, dec, hex, bin;
        if (!(w >> step >> name >> dec >> hex >> bin) || name.empty() || name[0] != '\\') continue;
        if (step.find_first_not_of("0123456789") != std::string::npos) continue;
        if (bin.find_first_not_of("01") != std::string::npos) continue;
        long long x = 0;
        for (char ch : bin) x = 2 * x + (ch - '0');
        if (bin.size() < 64 && bin[0] == '1') x -= 1LL << bin.size();
        v.push_back({std::stoi(step), name.substr(1), x});
    }
    return v;
}

}  // namespace hc::mutation
