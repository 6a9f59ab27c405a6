/* hc_bridge.h: the C entry points the VHDL testbench imports through VHPIDIRECT.
 *
 * One prefix (hc_), no overloads, plain C types: integers are VHDL `integer` (32 bits),
 * the observation buffer is a constrained std_ulogic_vector passed by reference as one
 * byte per element (0 'U', 1 'X', 2 '0', 3 '1', 4 'Z', 5 'W', 6 'L', 7 'H', 8 '-').
 * No C++ exception crosses this boundary: every entry point catches, records the error
 * and returns a failure code the testbench acts on.
 * Sizes: the testbench (VHDL) owns the observation width and passes it to hc_open, which
 * refuses to run when the C++ layout disagrees.
 */
#ifndef HC_BRIDGE_H
#define HC_BRIDGE_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Commands hc_next returns. */
enum { HC_CMD_WRITE = 0, HC_CMD_IDLE = 1, HC_CMD_END = 2 };
/* Largest observation the testbench buffer holds. */
enum { HC_OBS_MAX = 16384 };

/* Hands over generic number `index` of harris_top (harris_pkg order: IMG_WIDTH, IMG_HEIGHT,
 * SOBEL_W, M_PROD_W, M_DROP, BF_SUM_W, BF_DROP, RESP_W, KTR_W, K_SHIFT1, K_SHIFT2,
 * THR_SHIFT1, THR_SHIFT2). Returns 0. */
int32_t hc_generic(int32_t index, int32_t value);
/* Opens the session described by $HC_COSIM_CONFIG, checking the generics handed over and
 * the observation width against it. Returns 0 when the run can start. */
int32_t hc_open(int32_t obs_w);
/* The next bus cycle: HC_CMD_WRITE (then hc_data gives the word), HC_CMD_IDLE, HC_CMD_END. */
int32_t hc_next(void);
/* The data word of the current write, as a 32-bit two's-complement integer. */
int32_t hc_data(void);
/* The design's observation port after the cycle's clock edge. Returns 0 to go on, 1 to stop. */
int32_t hc_observe(const uint8_t* obs);
/* The observation port while the clock is low: after reset before the first edge
 * (after_reset = 1), or half-way between two edges when the port differs from what
 * hc_observe saw after the last edge (after_reset = 0). Registers change only on a rising
 * edge, so either must equal the model's state after the last write. Returns 0 to go on,
 * 1 to stop. */
int32_t hc_observe_held(const uint8_t* obs, int32_t after_reset);
/* Ends the session, writes the summary; returns the exit status: 0 pass, 1 mismatch, 2 error. */
int32_t hc_close(void);

#ifdef __cplusplus
}
#endif

#endif
