/* stage_bridge.h: the C entry points the entity-level testbenches (tests/rtl/<stem>_tb.vhd)
 * import through VHPIDIRECT.
 *
 * Purpose: one arithmetic stage entity per simulation, driven cycle by cycle from C++. The
 * C++ side (stage_bridge.cpp, stage_benches.cpp) generates every input vector, schedules the
 * control inputs (write and the enables), computes what the entity's outputs must be after
 * each cycle with the model's stage function (model/harris/<stem>.hpp), compares the outputs
 * the testbench hands back, and counts mismatches. The testbench only applies numbers to
 * ports, clocks, and packs outputs.
 *
 * One prefix (stage_), no overloads, plain C types: integers are VHDL `integer` (32 bits);
 * the outputs arrive as a constrained std_ulogic_vector passed by reference, one byte per
 * element (0 'U', 1 'X', 2 '0', 3 '1', 4 'Z', 5 'W', 6 'L', 7 'H', 8 '-'), element 0 being
 * the most significant bit of the first output port.
 * No C++ exception crosses this boundary: every entry point catches, records the error and
 * returns a value the testbench can go on with; stage_close then returns 2.
 * Sizes: the testbench (VHDL) owns the generics and hands them over before stage_open; the
 * C++ side derives the formats from them and refuses to run when the testbench's output
 * width disagrees with the one the model produces.
 *
 * The numbers below are owned here: CMake fills them into stage_bridge_pkg.vhd.in.
 */
#ifndef STAGE_BRIDGE_H
#define STAGE_BRIDGE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Entities (argument of stage_open). */
enum {
  STAGE_SOBEL_X = 0,
  STAGE_SOBEL_Y = 1,
  STAGE_M_PRODUCTS = 2,
  STAGE_BLOCK_FILTER = 3,
  STAGE_HARRIS_RESPONSE = 4,
  STAGE_THRESHOLD = 5,
  STAGE_LOCAL_MAXIMUM = 6
};

/* Generics and run parameters (first argument of stage_generic). The VHDL names are the
 * entities'; RANDOM_VECTORS and SEED are the testbench's own. */
enum {
  STAGE_G_SOBEL_W = 0,
  STAGE_G_M_PROD_W = 1,
  STAGE_G_M_DROP = 2,
  STAGE_G_IN_W = 3,      /* block_filter: M coefficient width */
  STAGE_G_BF_SUM_W = 4,
  STAGE_G_BF_DROP = 5,
  STAGE_G_BF_W = 6,      /* harris_response: block-sum width */
  STAGE_G_RESP_W = 7,
  STAGE_G_KTR_W = 8,
  STAGE_G_K_SHIFT1 = 9,
  STAGE_G_K_SHIFT2 = 10,
  STAGE_G_RANDOM_VECTORS = 11,
  STAGE_G_SEED = 12,
  STAGE_G_COUNT = 13
};

/* Largest packed output the testbench buffer holds (bits). */
enum { STAGE_OUT_MAX = 256 };

/* Hands over generic `index` (STAGE_G_*). Returns 0. */
int32_t stage_generic(int32_t index, int32_t value);
/* Opens the bench of `entity` (STAGE_*): builds the formats from the generics handed over,
 * checks `out_w` (the packed output width of the testbench) against the model. Returns 0
 * when the run can start. */
int32_t stage_open(int32_t entity, int32_t out_w);
/* Prepares the next cycle. Returns 1 when there is one, 0 when the run is over. */
int32_t stage_next(void);
/* Input `k` of the current cycle, in the entity's input order (see stage_benches.cpp):
 * control bits as 0/1, port values as the two's-complement integer of the port width. */
int32_t stage_input(int32_t k);
/* The packed outputs after the cycle. Returns 0 to go on, 1 to stop (internal error). */
int32_t stage_check(const uint8_t* out);
/* Ends the run and prints the summary; returns the exit status: 0 pass, 1 mismatch, 2 error. */
int32_t stage_close(void);

#ifdef __cplusplus
}
#endif

#endif
