-- harris_response_tb: entity-level bench of rtl/harris_response.vhd, driven from C++
-- (stage_bridge.h).
--
-- Purpose: proves harris_response (r = a*c - b*b - k*(a+c)^2 in two register steps) equals
-- the model's hc::harris_response_terms + hc::harris_response (model/harris/
-- harris_response.hpp) bit for bit. The C++ side chooses each cycle's inputs: write, en0,
-- en1, a, b, c over every BF_W-bit value. It runs the two steps as a pipeline: each write
-- applies a new vector with en0 = '1' while en1 = '1' registers the previous vector's r, so
-- r after a write is compared with the previous vector's response; the first write has
-- en1 = '0' (the step-1 registers have no reset) and a final one with en0 = '0' flushes.
-- Exit status: 0 pass, 1 mismatch, 2 error.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;
use work.stage_bridge_pkg.all;

entity harris_response_tb is
  generic (
    BF_W           : positive := bf_width(DEF_BF_SUM_W, DEF_BF_DROP);  --! block sum width
    RESP_W         : positive := DEF_RESP_W;                           --! response width
    KTR_W          : positive := DEF_KTR_W;                            --! k*tr^2 width
    K_SHIFT1       : natural  := DEF_K_SHIFT1;                         --! k = 2^-K_SHIFT1 + ...
    K_SHIFT2       : natural  := DEF_K_SHIFT2;                         --! ... + 2^-K_SHIFT2
    RANDOM_VECTORS : natural  := STAGE_DEF_RANDOM_VECTORS;             --! random vectors after the extremes
    SEED           : natural  := STAGE_DEF_SEED                        --! seed of the C++ generator
  );
end entity harris_response_tb;

architecture sim of harris_response_tb is
  constant OUT_W : positive := RESP_W;   -- packed outputs: r
  signal clk, rst, en0, en1, write : std_logic := '0';
  signal a, b, c : signed(BF_W - 1 downto 0) := (others => '0');
  signal r       : signed(RESP_W - 1 downto 0);
begin
  dut : entity work.harris_response
    generic map (BF_W => BF_W, RESP_W => RESP_W, KTR_W => KTR_W, K_SHIFT1 => K_SHIFT1,
                 K_SHIFT2 => K_SHIFT2)
    port map (clk => clk, rst => rst, en0 => en0, en1 => en1, write => write, a => a, b => b,
              c => c, r => r);

  drive : process is
    variable buf : stage_out_buf_t := (others => '0');
    variable rc  : integer;
  begin
    rc := stage_generic(STAGE_G_BF_W, BF_W);
    rc := stage_generic(STAGE_G_RESP_W, RESP_W);
    rc := stage_generic(STAGE_G_KTR_W, KTR_W);
    rc := stage_generic(STAGE_G_K_SHIFT1, K_SHIFT1);
    rc := stage_generic(STAGE_G_K_SHIFT2, K_SHIFT2);
    rc := stage_generic(STAGE_G_RANDOM_VECTORS, RANDOM_VECTORS);
    rc := stage_generic(STAGE_G_SEED, SEED);
    if stage_open(STAGE_HARRIS_RESPONSE, OUT_W) /= 0 then
      std.env.finish(2);
    end if;
    stage_reset(clk, rst);
    while stage_next = 1 loop
      write <= stage_bit(stage_input(0));
      en0   <= stage_bit(stage_input(1));
      en1   <= stage_bit(stage_input(2));
      a     <= to_signed(stage_input(3), BF_W);
      b     <= to_signed(stage_input(4), BF_W);
      c     <= to_signed(stage_input(5), BF_W);
      stage_clock(clk);
      buf(0 to OUT_W - 1) := std_ulogic_vector(r);
      exit when stage_check(buf) /= 0;
    end loop;
    std.env.finish(stage_close);
    wait;
  end process drive;
end architecture sim;
