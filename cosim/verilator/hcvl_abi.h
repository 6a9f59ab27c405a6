/* hcvl_abi.h: the C boundary between harris-cosim and one verilated netlist of harris_top.
 *
 * Purpose: each netlist configuration (image size, formats, OBSERVE, VHDL variant) is
 * synthesised by GHDL, verilated and compiled into its own shared object; the tool loads
 * it with dlopen(). The generated class is the same (Vhc) in every object, so the objects
 * cannot be linked into one program; this boundary is the only thing they share. One
 * prefix (hcvl_), no overloads, plain C types. Sizes are owned by the netlist side:
 * hcvl_obs_bits() says how wide the observation port came out of synthesis.
 */
#ifndef HCVL_ABI_H
#define HCVL_ABI_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever a signature below changes: the loader refuses other versions. */
#define HCVL_ABI_VERSION 1

typedef struct hcvl_design hcvl_design;

int hcvl_abi_version(void);
/* The configuration key the object was built for (checked by the loader). */
const char* hcvl_config_key(void);

hcvl_design* hcvl_new(void);
void hcvl_delete(hcvl_design* d);
/* Pulses rst = '0' (asynchronous, active low) with write = '0'. */
void hcvl_reset(hcvl_design* d);
/* One bus write: data on the bus, write = '1', one rising clock edge. */
void hcvl_write(hcvl_design* d, uint32_t data);
/* The corner port (what the host reads; reads do not clock the design). */
uint32_t hcvl_corner(const hcvl_design* d);
/* Width of the obs port in bits (1 when synthesised with OBSERVE = false). */
int hcvl_obs_bits(void);
/* Copies the obs port into words[0 .. (bits+31)/32 - 1]: Verilog bit b is bit b%32 of
 * words[b/32]. Verilog bit (bits-1) is VHDL obs(0), the first bit of the layout. */
void hcvl_obs(const hcvl_design* d, uint32_t* words);

#ifdef __cplusplus
}
#endif
#endif
