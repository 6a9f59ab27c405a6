// netlist.hpp: one Verilator build of harris_top per configuration, made on demand from the
// VHDL by GHDL's synthesis, cached, and loaded into the running program.
//
// Purpose: generics change the netlist (counter limits, widths), so every (geometry,
// formats, OBSERVE, VHDL variant) is its own build. build_netlist() runs
//   ghdl --synth --std=08 -gIMG_WIDTH=.. ... --out=verilog <rtl> -e harris_top
//     (bit strings as sized literals: cosim/ghdl_verilog.hpp)
//   verilator --cc (class Vhc) + make (Verilator's makefile, -j2) + c++ -shared
// in <cache>/<key>/, where key names the configuration and a hash of every input file,
// so an edited RTL file or harness gets a fresh build and an unchanged one is reused.
// VerilatedDesign dlopen()s the result and drives it through hcvl_abi.h.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "model/harris/harris_pkg.hpp"

namespace hc::vl {

namespace fs = std::filesystem;

/// What a netlist is built from.
struct NetlistConfig {
    Geometry g;
    Formats f;
    bool observe = true;              ///< OBSERVE generic: keep the obs port
    /// VHDL files that replace the rtl/ file declaring the same entity (test-only variants
    /// such as tests/rtl/m_products_sra.vhd).
    std::vector<fs::path> variants;
    /// Compile the verilated C++ with optimisation (-O2). Off for short streams such as
    /// the gate's, where the compile time is most of the cost; part of the key.
    bool optimise = true;
};

/// The VHDL files of the design in analysis order, with variants substituted. Throws
/// InputError when a variant does not exist or its entity is not one of the design's.
std::vector<fs::path> vhdl_sources(const NetlistConfig& c);

/// Cache key: "<W>x<H>_f<formats_hash>_<obs|noobs>[_O0]_<hash>": the formats hash covers every
/// field of format_fields(); the last hash covers the sources' contents,
/// the harness, the tool versions compiled in and how GHDL's Verilog is read (cosim::kVerilogReading).
std::string config_key(const NetlistConfig& c);

/// Where builds go: $HARRIS_COSIM_VL_CACHE, else the build tree's verilator-cache.
fs::path default_cache_dir();

/// Builds (or finds) the shared object for `c` and returns its path. Progress lines go to
/// `log`; a failing step throws std::runtime_error quoting the tail of its log file.
/// Concurrent callers are safe: each builds in a private directory renamed into place.
fs::path build_netlist(const NetlistConfig& c, const fs::path& cache_dir, std::ostream& log);

/// Does this machine have GHDL and Verilator (the build-time paths)?
bool toolchain_available(std::string* why = nullptr);

/// One loaded netlist instance (the design after reset).
class VerilatedDesign {
public:
    VerilatedDesign(const fs::path& so, const std::string& expected_key);
    ~VerilatedDesign();
    VerilatedDesign(const VerilatedDesign&) = delete;
    VerilatedDesign& operator=(const VerilatedDesign&) = delete;

    void reset();
    void write(std::uint32_t data) { write_(h_, data); }
    std::uint32_t corner() const { return corner_(h_); }
    int obs_bits() const { return obs_bits_; }
    /// obs as 32-bit words, Verilog bit b in words[b/32] bit b%32 (VHDL obs(0) is the top).
    const std::vector<std::uint32_t>& obs();

private:
    void* lib_ = nullptr;
    void* h_ = nullptr;
    void (*write_)(void*, std::uint32_t) = nullptr;
    std::uint32_t (*corner_)(const void*) = nullptr;
    void (*reset_)(void*) = nullptr;
    void (*obs_)(const void*, std::uint32_t*) = nullptr;
    void (*delete_)(void*) = nullptr;
    int obs_bits_ = 0;
    std::vector<std::uint32_t> obs_words_;
};

}  // namespace hc::vl
