// hcvl_design.cpp: the hcvl_ entry points over one verilated harris_top (class Vhc).
//
// Compiled once per netlist configuration, next to Verilator's output for it, into a
// shared object (see netlist_cache.cpp). HCVL_CONFIG_KEY is defined on the compile line.
#include "hcvl_abi.h"

#include <memory>

#include "Vhc.h"
#include "verilated.h"

#ifndef HCVL_CONFIG_KEY
#error "HCVL_CONFIG_KEY must be defined by the build"
#endif

struct hcvl_design {
    std::unique_ptr<VerilatedContext> ctx;
    std::unique_ptr<Vhc> top;
};

namespace {
// Width of obs as Verilator sees it; a 1-bit port is a plain CData.
template <class T>
void copy_port(const T& port, uint32_t* words) {
    if constexpr (sizeof(T) <= 8) {
        const auto v = static_cast<uint64_t>(port);
        words[0] = static_cast<uint32_t>(v);
        if constexpr (sizeof(T) == 8) words[1] = static_cast<uint32_t>(v >> 32);
    } else {
        for (size_t i = 0; i < sizeof(T) / sizeof(EData); ++i) words[i] = port.m_storage[i];
    }
}
}  // namespace

extern "C" {

int hcvl_abi_version(void) { return HCVL_ABI_VERSION; }
const char* hcvl_config_key(void) { return HCVL_CONFIG_KEY; }

hcvl_design* hcvl_new(void) {
    auto* d = new hcvl_design;
    d->ctx = std::make_unique<VerilatedContext>();
    d->top = std::make_unique<Vhc>(d->ctx.get(), "harris_top");
    d->top->clk = 0;
    d->top->rst = 1;
    d->top->write = 0;
    d->top->data = 0;
    d->top->eval();
    return d;
}

void hcvl_delete(hcvl_design* d) {
    if (!d) return;
    d->top->final();
    delete d;
}

void hcvl_reset(hcvl_design* d) {
    d->top->write = 0;
    d->top->rst = 0;
    d->top->eval();
    d->top->rst = 1;
    d->top->eval();
}

void hcvl_write(hcvl_design* d, uint32_t data) {
    // clk is low between calls. The bus word and write = '1' go in with the falling half
    // of the cycle, then one rising edge steps every register. write stays '1' afterwards:
    // reads do not clock the design, and leaving the inputs alone makes the falling-edge
    // eval a no-op for the combinational logic (only clk changes), about half the cost.
    Vhc& t = *d->top;
    t.data = data;
    t.write = 1;
    t.eval();
    t.clk = 1;
    t.eval();
    t.clk = 0;
}

uint32_t hcvl_corner(const hcvl_design* d) { return d->top->corner; }

int hcvl_obs_bits(void) { return HCVL_OBS_BITS; }

void hcvl_obs(const hcvl_design* d, uint32_t* words) { copy_port(d->top->obs, words); }

}  // extern "C"
