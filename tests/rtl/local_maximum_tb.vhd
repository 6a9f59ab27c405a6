-- local_maximum_tb: entity-level bench of rtl/local_maximum.vhd, driven from C++
-- (stage_bridge.h).
--
-- Purpose: proves local_maximum (corner = '1' when the centre is strictly greater than its
-- 8 neighbours; combinational) equals the model's hc::local_maximum
-- (model/harris/local_maximum.hpp) bit for bit. The C++ side chooses the nine RESP_W-bit
-- inputs r11..r33 (row-major) of each step: two-level windows (every tie pattern), uniform
-- values, values in -2..2 (ties) and centres next to the neighbours' maximum. No clock:
-- each step applies the inputs, waits STAGE_HALF for the output to settle and compares
-- corner. Exit status: 0 pass, 1 mismatch, 2 error.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;
use work.stage_bridge_pkg.all;

entity local_maximum_tb is
  generic (
    RESP_W         : positive := DEF_RESP_W;                 --! response width (the DUT's)
    RANDOM_VECTORS : natural  := STAGE_DEF_RANDOM_VECTORS;   --! random vectors after the extremes
    SEED           : natural  := STAGE_DEF_SEED              --! seed of the C++ generator
  );
end entity local_maximum_tb;

architecture sim of local_maximum_tb is
  constant OUT_W : positive := 1;   -- packed outputs: corner
  signal r      : s_matrix3(open)(RESP_W - 1 downto 0) := (others => (others => (others => '0')));
  signal corner : std_logic;
begin
  dut : entity work.local_maximum
    generic map (RESP_W => RESP_W)
    port map (r => r, corner => corner);

  drive : process is
    variable buf : stage_out_buf_t := (others => '0');
    variable rc  : integer;
  begin
    rc := stage_generic(STAGE_G_RESP_W, RESP_W);
    rc := stage_generic(STAGE_G_RANDOM_VECTORS, RANDOM_VECTORS);
    rc := stage_generic(STAGE_G_SEED, SEED);
    if stage_open(STAGE_LOCAL_MAXIMUM, OUT_W) /= 0 then
      std.env.finish(2);
    end if;
    while stage_next = 1 loop
      for k in 0 to 8 loop
        r(k / 3 + 1, k mod 3 + 1) <= to_signed(stage_input(k), RESP_W);
      end loop;
      wait for STAGE_HALF;   -- combinational: inputs and corner settle
      buf(0) := corner;
      exit when stage_check(buf) /= 0;
    end loop;
    std.env.finish(stage_close);
    wait;
  end process drive;
end architecture sim;
