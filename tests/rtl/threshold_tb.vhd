-- threshold_tb: entity-level bench of rtl/threshold.vhd, driven from C++ (stage_bridge.h).
--
-- Purpose: proves threshold (r0 delayed one write; on an enabled write r1 takes the delayed
-- r0 if it is >= thr, else 0; on a write with en = '0' r1 becomes 0) equals the model's
-- hc::threshold (model/harris/threshold.hpp) bit for bit. The C++ side chooses each cycle's
-- inputs: write, en, r0, thr over every RESP_W-bit value. Because of the delay, vector
-- (r, thr) is applied as r0 = r on one write and thr = thr (with en = '1', and the next
-- vector's r0) on the next; r1 is compared after that second write. Hold checks: write =
-- '0' (r1 keeps its value) and en = '0' (r1 must be 0). Exit status: 0 pass, 1 mismatch,
-- 2 error.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;
use work.stage_bridge_pkg.all;

entity threshold_tb is
  generic (
    RESP_W         : positive := DEF_RESP_W;                 --! response width (the DUT's)
    RANDOM_VECTORS : natural  := STAGE_DEF_RANDOM_VECTORS;   --! random vectors after the extremes
    SEED           : natural  := STAGE_DEF_SEED              --! seed of the C++ generator
  );
end entity threshold_tb;

architecture sim of threshold_tb is
  constant OUT_W : positive := RESP_W;   -- packed outputs: r1
  signal clk, rst, en, write : std_logic := '0';
  signal r0, thr : signed(RESP_W - 1 downto 0) := (others => '0');
  signal r1      : signed(RESP_W - 1 downto 0);
begin
  dut : entity work.threshold
    generic map (RESP_W => RESP_W)
    port map (clk => clk, rst => rst, en => en, write => write, r0 => r0, thr => thr, r1 => r1);

  drive : process is
    variable buf : stage_out_buf_t := (others => '0');
    variable rc  : integer;
  begin
    rc := stage_generic(STAGE_G_RESP_W, RESP_W);
    rc := stage_generic(STAGE_G_RANDOM_VECTORS, RANDOM_VECTORS);
    rc := stage_generic(STAGE_G_SEED, SEED);
    if stage_open(STAGE_THRESHOLD, OUT_W) /= 0 then
      std.env.finish(2);
    end if;
    stage_reset(clk, rst);
    while stage_next = 1 loop
      write <= stage_bit(stage_input(0));
      en    <= stage_bit(stage_input(1));
      r0    <= to_signed(stage_input(2), RESP_W);
      thr   <= to_signed(stage_input(3), RESP_W);
      stage_clock(clk);
      buf(0 to OUT_W - 1) := std_ulogic_vector(r1);
      exit when stage_check(buf) /= 0;
    end loop;
    std.env.finish(stage_close);
    wait;
  end process drive;
end architecture sim;
