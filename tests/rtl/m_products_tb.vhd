-- m_products_tb: entity-level bench of rtl/m_products.vhd, driven from C++ (stage_bridge.h).
--
-- Purpose: proves m_products (a = ix*ix, b = ix*iy, c = iy*iy, each resized to M_PROD_W and
-- cut by M_DROP LSBs, registered) equals the model's hc::m_products
-- (model/harris/m_products.hpp) bit for bit. The C++ side chooses each cycle's inputs:
-- write, en, ix, iy, drawn over every SOBEL_W-bit value (not only the +-1020 a Sobel stage
-- gives, so that numeric_std's resize wrap is compared too), plus the extreme pairs and
-- hold checks. Outputs are packed a & b & c. Run with -gSOBEL_W=9 -gM_PROD_W=17 (say) to
-- check another format: the generics go to the DUT and, through stage_generic, to the
-- C++ formats. Exit status: 0 pass, 1 mismatch, 2 error.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;
use work.stage_bridge_pkg.all;

entity m_products_tb is
  generic (
    SOBEL_W        : positive := DEF_SOBEL_W;                --! gradient width (the DUT's)
    M_PROD_W       : positive := DEF_M_PROD_W;               --! product width before the cut
    M_DROP         : natural  := DEF_M_DROP;                 --! LSBs dropped after the product
    RANDOM_VECTORS : natural  := STAGE_DEF_RANDOM_VECTORS;   --! random vectors after the extremes
    SEED           : natural  := STAGE_DEF_SEED              --! seed of the C++ generator
  );
end entity m_products_tb;

architecture sim of m_products_tb is
  constant M_W   : positive := m_width(M_PROD_W, M_DROP);
  constant OUT_W : positive := 3 * M_W;   -- packed outputs: a & b & c
  signal clk, rst, en, write : std_logic := '0';
  signal ix, iy  : signed(SOBEL_W - 1 downto 0) := (others => '0');
  signal a, b, c : signed(M_W - 1 downto 0);
begin
  dut : entity work.m_products
    generic map (SOBEL_W => SOBEL_W, M_PROD_W => M_PROD_W, M_DROP => M_DROP)
    port map (clk => clk, rst => rst, en => en, write => write, ix => ix, iy => iy,
              a => a, b => b, c => c);

  drive : process is
    variable buf : stage_out_buf_t := (others => '0');
    variable rc  : integer;
  begin
    rc := stage_generic(STAGE_G_SOBEL_W, SOBEL_W);
    rc := stage_generic(STAGE_G_M_PROD_W, M_PROD_W);
    rc := stage_generic(STAGE_G_M_DROP, M_DROP);
    rc := stage_generic(STAGE_G_RANDOM_VECTORS, RANDOM_VECTORS);
    rc := stage_generic(STAGE_G_SEED, SEED);
    if stage_open(STAGE_M_PRODUCTS, OUT_W) /= 0 then
      std.env.finish(2);
    end if;
    stage_reset(clk, rst);
    while stage_next = 1 loop
      write <= stage_bit(stage_input(0));
      en    <= stage_bit(stage_input(1));
      ix    <= to_signed(stage_input(2), SOBEL_W);
      iy    <= to_signed(stage_input(3), SOBEL_W);
      stage_clock(clk);
      buf(0 to OUT_W - 1) := std_ulogic_vector(a) & std_ulogic_vector(b) & std_ulogic_vector(c);
      exit when stage_check(buf) /= 0;
    end loop;
    std.env.finish(stage_close);
    wait;
  end process drive;
end architecture sim;
