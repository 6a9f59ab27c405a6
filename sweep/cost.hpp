// cost.hpp: the hardware cost of a configuration: harris_top (OBSERVE=false) synthesised
// by GHDL to Verilog, then by yosys `synth_xilinx` (hierarchy kept) for the 7-series (the thesis's
// Zynq XC7Z020), cached per configuration; plus an analytic count of datapath register bits.
//
// Flow (docs/bit-widths.md, "Cost"):
//   ghdl --synth --std=08 -gIMG_WIDTH=.. -gSOBEL_W=.. ... -gOBSERVE=false --out=verilog
//        rtl/harris_pkg.vhd ... rtl/harris_top.vhd -e harris_top        > harris_top.v
//   [GHDL's bit-string constants wider than 32 bits as sized literals: cosim::synth_verilog]
//   [variant "signed": rewrite GHDL's multiplications of sign-extended operands into
//    $signed(a) * $signed(b) -- see rewrite_signed_multiplies]
//   yosys -p "read_verilog harris_top.v; synth_xilinx -top harris_top; stat -json"
// The cache key hashes the flow's version and variant, how GHDL's Verilog is read
// (cosim::kVerilogReading), the generics, the contents of every
// RTL file and the GHDL and yosys version lines: an edited RTL file or tool gets a fresh
// synthesis, an unchanged configuration is read back from <cache>/<key>.json.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/harris/harris_pkg.hpp"

namespace hc::sweep {

enum class Variant {
    signed_mul,   ///< GHDL's Verilog with signed multiplies restored (what a VHDL synthesiser infers)
    ghdl,         ///< GHDL's Verilog as emitted
};
std::string variant_name(Variant v);

struct CostOptions {
    std::vector<std::filesystem::path> rtl_sources;   ///< rtl/*.vhd in analysis order (cosim::rtl_sources())
    std::filesystem::path cache_dir;
    Geometry geometry{};                           ///< IMG_WIDTH / IMG_HEIGHT generics
    std::string ghdl = "ghdl", yosys = "yosys";
};

/// yosys cell counts after synth_xilinx, summed over the hierarchy.
struct Cost {
    long luts = 0;      ///< LUT1..LUT6 (logic LUTs, without INV)
    long inv = 0;       ///< INV cells (yosys keeps inverters on async resets as cells; a LUT1 each)
    long ffs = 0;       ///< FDRE + FDSE + FDCE + FDPE
    long dsps = 0;      ///< DSP48E1
    long carry4 = 0;    ///< CARRY4 (carry-chain segments of 4 bits)
    long muxf = 0;      ///< MUXF7 + MUXF8
    long srl = 0;       ///< SRL16E / SRLC32E (shift registers in LUTs)
    std::map<std::string, long> cells;   ///< every cell type
    double seconds = 0;   ///< synthesis wall time (when it ran; the cached run's time otherwise)
    bool cached = false;
    std::string key;
};
/// Its JSON (a shard's result): one key a field, by the field's name.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(Cost, luts, inv, ffs, dsps, carry4, muxf, srl, cells, seconds, cached, key)

/// The tool versions and RTL contents the key depends on; computed once per sweep.
struct CostContext {
    CostOptions opt;
    std::string fingerprint;   ///< tools' version lines + RTL file contents
    explicit CostContext(const CostOptions& o);   ///< throws SimulatorError if a tool is missing
};

/// The cache key of a configuration (16 hex digits).
std::string cost_key(const CostContext& ctx, const Formats& f, Variant v);
/// Cost of one configuration: from the cache, else synthesised (several minutes of CPU at
/// most; one core). Throws SimulatorError naming the log file when a tool fails.
Cost synth_cost(const CostContext& ctx, const Formats& f, Variant v);
/// The cached result, if any.
bool cached_cost(const CostContext& ctx, const Formats& f, Variant v, Cost& out);

/// GHDL writes `signed(a) * signed(b)` as an unsigned product of operands sign-extended to
/// the result width (`{{11{ix[10]}}, ix} * {{11{iy[10]}}, iy}`, 22x22 bits); yosys then
/// maps a 22x22 multiplier (two DSP48E1 and adders) where 11x11 signed fits one. This
/// rewrites every such product whose operands are both plain sign extensions into
/// `$signed(a) * $signed(b)`, which is the same value in the result's width (a signed
/// product of widths m and n fits in m + n bits). Returns the number rewritten.
int rewrite_signed_multiplies(std::string& verilog);

/// Register bits of the format-dependent datapath as declared in the RTL (before any
/// synthesis optimisation): Sobel 2x25, M 3x25, block sums 3x9, per response a*c, b*b,
/// k-term, r, the threshold stage's two registers, find-max's running/max and counter.
/// The format-independent registers (input converters 4x49x8, control) are not included.
long datapath_register_bits(const Formats& f, const Geometry& g);

}  // namespace hc::sweep
