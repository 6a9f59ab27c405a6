// netlist.cpp: GHDL synthesis -> Verilator -> shared object, cached by configuration.
#include "netlist.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "hcvl_abi.h"

// Tool paths and directories come from cosim/verilator/CMakeLists.txt (find_program).
#ifndef HCVL_GHDL
#error "HCVL_GHDL, HCVL_VERILATOR, HCVL_MAKE, HCVL_CXX, HCVL_RTL_DIR, HCVL_SRC_DIR, HCVL_CACHE_DIR"
#endif

namespace hc::vl {

namespace {

// Analysis order of rtl/ (a package, then each entity after those it instantiates).
constexpr std::array<const char*, 15> kRtlOrder = {
    "harris_pkg",         "load_control",   "input_converter",   "input_converter_mux",
    "control_shift_register", "sobel_x",    "sobel_y",           "m_products",
    "block_filter",       "harris_response", "find_max",         "threshold",
    "local_maximum",      "corner_shift_register", "harris_top"};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read '" + p.string() + "'");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The entity a VHDL file declares (the first `entity NAME is`), lower case.
std::string declared_entity(const fs::path& p) {
    static const std::regex re(R"(^\s*entity\s+(\w+)\s+is)", std::regex::icase | std::regex::multiline);
    const std::string text = slurp(p);
    std::smatch m;
    if (!std::regex_search(text, m, re))
        throw std::invalid_argument("variant '" + p.string() + "' declares no entity");
    std::string e = m[1];
    for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return e;
}

// FNV-1a 64: a content hash for the cache key (not a security boundary).
std::uint64_t fnv1a(const std::string& s, std::uint64_t h = 1469598103934665603ULL) {
    for (unsigned char ch : s) {
        h ^= ch;
        h *= 1099511628211ULL;
    }
    return h;
}

// Runs argv with cwd, stdout to `out` (or the log), stderr to the log. Returns exit status.
int run(const std::vector<std::string>& argv, const fs::path& cwd, const fs::path& log,
        const fs::path& out = {}) {
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        if (chdir(cwd.c_str()) != 0) _exit(126);
        const int lfd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        const int ofd = out.empty() ? lfd : open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (lfd < 0 || ofd < 0) _exit(126);
        dup2(ofd, 1);
        dup2(lfd, 2);
        std::vector<char*> args;
        for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execvp(args[0], args.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) throw std::runtime_error("waitpid failed");
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string tail(const fs::path& p, std::size_t n = 2000) {
    std::string s;
    try {
        s = slurp(p);
    } catch (...) {
        return "(no log)";
    }
    return s.size() > n ? "..." + s.substr(s.size() - n) : s;
}

void step(const std::vector<std::string>& argv, const fs::path& cwd, const fs::path& log,
          const std::string& what, const fs::path& out = {}) {
    {
        std::ofstream l(log, std::ios::app);
        l << "\n$";
        for (const auto& a : argv) l << ' ' << a;
        l << '\n';
    }
    const int rc = run(argv, cwd, log, out);
    if (rc != 0)
        throw std::runtime_error(what + " failed (exit " + std::to_string(rc) + "); log " + log.string() +
                                 ":\n" + tail(log));
}

// Width of the obs port as GHDL wrote it: "output [N:0] obs" (or "output obs": 1 bit).
int obs_bits_of(const fs::path& verilog) {
    const std::string v = slurp(verilog);
    static const std::regex wide(R"(output\s+\[(\d+):0\]\s+obs\s*\))");
    static const std::regex one(R"(output\s+obs\s*\))");
    std::smatch m;
    if (std::regex_search(v, m, wide)) return std::stoi(m[1]) + 1;
    if (std::regex_search(v, m, one)) return 1;
    throw std::runtime_error("no obs port in " + verilog.string());
}

}  // namespace

std::vector<fs::path> vhdl_sources(const NetlistConfig& c) {
    std::vector<fs::path> files;
    for (const char* e : kRtlOrder) files.push_back(fs::path(HCVL_RTL_DIR) / (std::string(e) + ".vhd"));
    for (const auto& v : c.variants) {
        if (!fs::is_regular_file(v)) throw std::invalid_argument("variant '" + v.string() + "' does not exist");
        const std::string e = declared_entity(v);
        bool found = false;
        for (std::size_t k = 0; k < kRtlOrder.size(); ++k)
            if (e == kRtlOrder[k]) {
                files[k] = fs::absolute(v);
                found = true;
            }
        if (!found)
            throw std::invalid_argument("variant '" + v.string() + "' declares entity '" + e +
                                        "', which is not an entity of harris_top");
    }
    return files;
}

std::string config_key(const NetlistConfig& c) {
    const Formats& f = c.f;
    std::ostringstream k;
    k << c.g.width << 'x' << c.g.height << "_s" << f.sobel_w << "m" << f.m_prod_w << '-' << f.m_drop << "b"
      << f.bf_sum_w << '-' << f.bf_drop << "r" << f.resp_w << "k" << f.ktr_w << '-' << f.k_shift1 << '-'
      << f.k_shift2 << "t" << f.thr_shift1 << '-' << f.thr_shift2 << (c.observe ? "_obs" : "_noobs");
    std::uint64_t h = fnv1a(HCVL_TOOL_VERSIONS);
    for (const auto& p : vhdl_sources(c)) h = fnv1a(p.filename().string() + slurp(p), h);
    for (const char* p : {"hcvl_design.cpp", "hcvl_abi.h"}) h = fnv1a(slurp(fs::path(HCVL_SRC_DIR) / p), h);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    k << '_' << std::string(hex, 10);
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

    // 1. GHDL synthesis of the VHDL with this configuration's generics, to Verilog.
    std::vector<std::string> synth = {HCVL_GHDL, "--synth", "--std=08"};
    for (const auto& [name, value] : generics(c.g, c.f)) synth.push_back("-g" + name + "=" + std::to_string(value));
    synth.push_back(std::string("-gOBSERVE=") + (c.observe ? "true" : "false"));
    synth.push_back("--out=verilog");
    for (const auto& p : vhdl_sources(c)) synth.push_back(p.string());
    synth.insert(synth.end(), {"-e", "harris_top"});
    step(synth, tmp, lg, "GHDL synthesis", tmp / "harris_top.v");
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
    // 3. Compile with Verilator's makefile (never more than 2 jobs: shared machine), -O2.
    step({HCVL_MAKE, "-C", "obj", "-f", "Vhc.mk", "-j2", "OPT_FAST=-O2", "OPT_SLOW=-O1", "OPT_GLOBAL=-O2",
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
