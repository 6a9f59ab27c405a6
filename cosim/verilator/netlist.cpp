// netlist.cpp: GHDL synthesis -> Verilator -> shared object, cached by configuration.
#include "cosim/verilator/netlist.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "cosim/cosim.hpp"
#include "cosim/ghdl_verilog.hpp"
#include "cosim/verilator/hcvl_abi.h"
#include "model/util/util.hpp"

// Tool paths and directories come from cosim/verilator/CMakeLists.txt (find_program).
#ifndef HCVL_GHDL
#error "HCVL_GHDL, HCVL_VERILATOR, HCVL_MAKE, HCVL_CXX, HCVL_SRC_DIR, HCVL_CACHE_DIR"
#endif

namespace hc::vl {

namespace {

// The entity a VHDL file declares (the first `entity NAME is`), lower case.
std::string declared_entity(const fs::path& p) {
    static const std::regex re(R"(^\s*entity\s+(\w+)\s+is)", std::regex::icase | std::regex::multiline);
    const std::string text = util::read_file(p);
    std::smatch m;
    if (!std::regex_search(text, m, re))
        throw InputError("variant '" + p.string() + "' declares no entity");
    std::string e = m[1];
    for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return e;
}

void step(const std::vector<std::string>& argv, const fs::path& cwd, const fs::path& log,
          const std::string& what, const fs::path& out = {}) {
    {
        std::ofstream l(log, std::ios::app);
        l << "\n$";
        for (const auto& a : argv) l << ' ' << a;
        l << '\n';
    }
    const int rc = util::run_process(argv, {.cwd = cwd, .log = log, .stdout_file = out});
    if (rc != 0)
        throw SimulatorError(what + " failed (exit " + std::to_string(rc) + "); log " + log.string() + ":\n" +
                             util::log_tail(log));
}

// Width of the obs port as GHDL wrote it: "output [N:0] obs" (or "output obs": 1 bit).
int obs_bits_of(const fs::path& verilog) {
    const std::string v = util::read_file(verilog);
    static const std::regex wide(R"(output\s+\[(\d+):0\]\s+obs\s*\))");
    static const std::regex one(R"(output\s+obs\s*\))");
    std::smatch m;
    if (std::regex_search(v, m, wide)) return std::stoi(m[1]) + 1;
    if (std::regex_search(v, m, one)) return 1;
    throw std::runtime_error("no obs port in " + verilog.string());
}

}  // namespace

std::vector<fs::path> vhdl_sources(const NetlistConfig& c) {
    std::vector<fs::path> files = cosim::rtl_sources();
    for (const auto& v : c.variants) {
        if (!fs::is_regular_file(v)) throw InputError("variant '" + v.string() + "' does not exist");
        const std::string e = declared_entity(v);
        bool found = false;
        for (std::size_t k = 0; k < files.size(); ++k)
            if (e == files[k].stem().string()) {
                files[k] = fs::absolute(v);
                found = true;
            }
        if (!found)
            throw InputError("variant '" + v.string() + "' declares entity '" + e +
                                        "', which is not an entity of harris_top");
    }
    return files;
}

std::string config_key(const NetlistConfig& c) {
    std::ostringstream k;
    k << c.g.width << 'x' << c.g.height << "_f" << util::hex64(formats_hash(c.f)).substr(0, 10)
      << (c.observe ? "_obs" : "_noobs") << (c.optimise ? "" : "_O0");
    std::uint64_t h = util::fnv1a(std::string(HCVL_TOOL_VERSIONS) + cosim::kVerilogReading);
    for (const auto& p : vhdl_sources(c)) h = util::fnv1a(p.filename().string() + util::read_file(p), h);
    for (const char* p : {"hcvl_design.cpp", "hcvl_abi.h"}) h = util::fnv1a(util::read_file(fs::path(HCVL_SRC_DIR) / p), h);
    k << '_' << util::hex64(h).substr(0, 10);
    return k.str();
}

fs::path default_cache_dir() {
    if (const char* env = std::getenv("HARRIS_COSIM_VL_CACHE"); env && *env) return env;
    return HCVL_CACHE_DIR;
}

bool toolchain_available(std::string* why) {
    for (const char* t : {HCVL_GHDL, HCVL_VERILATOR, HCVL_MAKE})
        if (std::string(t).empty() || std::string(t).find("NOTFOUND") != std::string::npos ||
            access(t, X_OK) != 0) {
            if (why) *why = std::string("tool not found: ") + t;
            return false;
        }
    return true;
}

fs::path build_netlist(const NetlistConfig& c, const fs::path& cache_dir, std::ostream& log) {
    c.g.validate();
    c.f.validate();
    std::string why;
    if (!toolchain_available(&why)) throw std::runtime_error(why);
    const std::string key = config_key(c);
    const fs::path dir = cache_dir / key, so = dir / "libhcvl.so";
    if (fs::exists(so)) return so;

    fs::create_directories(cache_dir);
    const fs::path tmp = cache_dir / (key + ".tmp" + std::to_string(getpid()));
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    const fs::path lg = tmp / "build.log";
    log << "verilator: building netlist " << key << " in " << cache_dir.string() << '\n' << std::flush;

    // 1. GHDL synthesis of the VHDL with this configuration's generics, to Verilog (its bit
    //    strings as sized literals, cosim/ghdl_verilog.hpp).
    std::vector<std::string> synth = {HCVL_GHDL, "--synth", "--std=08"};
    for (const auto& [name, value] : generics(c.g, c.f)) synth.push_back("-g" + name + "=" + std::to_string(value));
    synth.push_back(std::string("-gOBSERVE=") + (c.observe ? "true" : "false"));
    synth.push_back("--out=verilog");
    for (const auto& p : vhdl_sources(c)) synth.push_back(p.string());
    synth.insert(synth.end(), {"-e", "harris_top"});
    step(synth, tmp, lg, "GHDL synthesis", tmp / "harris_top.v");
    util::write_file_atomic(tmp / "harris_top.v", cosim::sized_bit_literals(util::read_file(tmp / "harris_top.v")));
    const int obs_bits = obs_bits_of(tmp / "harris_top.v");

    // 2. Verilator: C++ model of the netlist as class Vhc, plus the hcvl_ harness.
    //    -O3 and --x-assign/--x-initial fast: speed; X never reaches a compared bit because
    //    the model marks the registers without reset as undefined until written.
    const std::string cflags = "-fPIC -DHCVL_CONFIG_KEY=\\\"" + key + "\\\" -DHCVL_OBS_BITS=" +
                               std::to_string(obs_bits) + " -I" + HCVL_SRC_DIR;
    step({HCVL_VERILATOR, "--cc", "harris_top.v", "--top-module", "harris_top", "--prefix", "Vhc", "-O3",
          "--x-assign", "fast", "--x-initial", "fast", "--noassert", "-Wno-fatal", "-Wno-lint", "-Wno-style",
          "--Mdir", "obj", "-CFLAGS", cflags, std::string(HCVL_SRC_DIR) + "/hcvl_design.cpp"},
         tmp, lg, "Verilator");
    // 3. Compile with Verilator's makefile (never more than 2 jobs: shared machine), -O2
    //    (-O0 when c.optimise is off: a short stream runs in less time than -O2 compiles).
    const std::string o_fast = c.optimise ? "-O2" : "-O0", o_slow = c.optimise ? "-O1" : "-O0";
    step({HCVL_MAKE, "-C", "obj", "-f", "Vhc.mk", "-j2", "OPT_FAST=" + o_fast, "OPT_SLOW=" + o_slow, "OPT_GLOBAL=" + o_fast,
          "Vhc__ALL.a", "hcvl_design.o", "verilated.o", "verilated_threads.o"},
         tmp, lg, "compiling the verilated netlist");
    // 4. One shared object; Verilator's runtime symbols stay private to it.
    step({HCVL_CXX, "-shared", "-o", "libhcvl.so", "obj/hcvl_design.o", "obj/Vhc__ALL.a", "obj/verilated.o",
          "obj/verilated_threads.o", "-pthread", "-Wl,--exclude-libs,ALL"},
         tmp, lg, "linking the netlist library");

    std::error_code ec;
    fs::rename(tmp, dir, ec);
    if (ec) {   // another process finished the same key first: use theirs
        fs::remove_all(tmp);
        if (!fs::exists(so)) throw std::runtime_error("cannot install " + dir.string() + ": " + ec.message());
    }
    log << "verilator: built " << so.string() << '\n' << std::flush;
    return so;
}

// ---- loading --------------------------------------------------------------------------

VerilatedDesign::VerilatedDesign(const fs::path& so, const std::string& expected_key) {
    // RTLD_LOCAL: two netlists (e.g. the gate's and the run's) each keep their own Vhc.
    lib_ = dlopen(so.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib_) throw std::runtime_error(std::string("cannot load netlist: ") + dlerror());
    auto sym = [&](const char* name) {
        void* p = dlsym(lib_, name);
        if (!p) throw std::runtime_error(so.string() + " lacks " + name);
        return p;
    };
    const auto version = reinterpret_cast<int (*)()>(sym("hcvl_abi_version"))();
    if (version != HCVL_ABI_VERSION)
        throw std::runtime_error(so.string() + " has ABI version " + std::to_string(version) + ", expected " +
                                 std::to_string(HCVL_ABI_VERSION));
    const std::string key = reinterpret_cast<const char* (*)()>(sym("hcvl_config_key"))();
    if (!expected_key.empty() && key != expected_key)
        throw std::runtime_error(so.string() + " was built for " + key + ", not " + expected_key);
    auto make = reinterpret_cast<void* (*)()>(sym("hcvl_new"));
    delete_ = reinterpret_cast<void (*)(void*)>(sym("hcvl_delete"));
    reset_ = reinterpret_cast<void (*)(void*)>(sym("hcvl_reset"));
    write_ = reinterpret_cast<void (*)(void*, std::uint32_t)>(sym("hcvl_write"));
    corner_ = reinterpret_cast<std::uint32_t (*)(const void*)>(sym("hcvl_corner"));
    obs_ = reinterpret_cast<void (*)(const void*, std::uint32_t*)>(sym("hcvl_obs"));
    obs_bits_ = reinterpret_cast<int (*)()>(sym("hcvl_obs_bits"))();
    obs_words_.assign(static_cast<std::size_t>((obs_bits_ + 31) / 32), 0);
    h_ = make();
    reset();
}

VerilatedDesign::~VerilatedDesign() {
    if (h_) delete_(h_);
    // the library stays loaded: Verilator registers atexit handlers inside it
}

void VerilatedDesign::reset() { reset_(h_); }

const std::vector<std::uint32_t>& VerilatedDesign::obs() {
    obs_(h_, obs_words_.data());
    return obs_words_;
}

}  // namespace hc::vl
