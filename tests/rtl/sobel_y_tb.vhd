-- sobel_y_tb: entity-level bench of rtl/sobel_y.vhd, driven from C++ (stage_bridge.h).
--
-- Purpose: proves sobel_y (iy = [+1 +2 +1; 0 0 0; -1 -2 -1] * a, registered) equals the model's
-- hc::sobel_y (model/harris/sobel_y.hpp) bit for bit. The C++ side chooses each cycle's
-- inputs: write, en, then the nine pixels a11..a33 row-major; it schedules the extreme
-- windows, RANDOM_VECTORS random ones and hold checks (write = '0' or en = '0', where iy
-- must keep its value), and compares iy after every rising edge. The exit status is the
-- bridge's: 0 pass, 1 mismatch, 2 error.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;
use work.stage_bridge_pkg.all;

entity sobel_y_tb is
  generic (
    SOBEL_W        : positive := DEF_SOBEL_W;                --! gradient width (the DUT's)
    RANDOM_VECTORS : natural  := STAGE_DEF_RANDOM_VECTORS;   --! random vectors after the extremes
    SEED           : natural  := STAGE_DEF_SEED              --! seed of the C++ generator
  );
end entity sobel_y_tb;

architecture sim of sobel_y_tb is
  constant OUT_W : positive := SOBEL_W;   -- packed outputs: iy
  signal clk, rst, en, write : std_logic := '0';
  signal a  : u8_matrix3 := (others => (others => (others => '0')));
  signal iy : signed(SOBEL_W - 1 downto 0);
begin
  dut : entity work.sobel_y
    generic map (SOBEL_W => SOBEL_W)
    port map (clk => clk, rst => rst, en => en, write => write, a => a, iy => iy);

  drive : process is
    variable buf : stage_out_buf_t := (others => '0');
    variable rc  : integer;
  begin
    rc := stage_generic(STAGE_G_SOBEL_W, SOBEL_W);
    rc := stage_generic(STAGE_G_RANDOM_VECTORS, RANDOM_VECTORS);
    rc := stage_generic(STAGE_G_SEED, SEED);
    if stage_open(STAGE_SOBEL_Y, OUT_W) /= 0 then
      std.env.finish(2);
    end if;
    stage_reset(clk, rst);
    while stage_next = 1 loop
      write <= stage_bit(stage_input(0));
      en    <= stage_bit(stage_input(1));
      for k in 0 to 8 loop
        a(k / 3 + 1, k mod 3 + 1) <= to_unsigned(stage_input(2 + k), PIXEL_W);
      end loop;
      stage_clock(clk);
      buf(0 to OUT_W - 1) := std_ulogic_vector(iy);
      exit when stage_check(buf) /= 0;
    end loop;
    std.env.finish(stage_close);
    wait;
  end process drive;
end architecture sim;
