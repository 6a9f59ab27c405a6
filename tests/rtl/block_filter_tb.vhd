-- block_filter_tb: entity-level bench of rtl/block_filter.vhd, driven from C++ (stage_bridge.h).
--
-- Purpose: proves block_filter (the nine IN_W inputs summed in BF_SUM_W bits, BF_DROP LSBs
-- dropped, registered) equals the model's hc::block_filter (model/harris/block_filter.hpp)
-- bit for bit. The C++ side chooses each cycle's inputs: write, en, then a11..a33 row-major,
-- over every IN_W-bit value (sums that wrap in BF_SUM_W bits included), plus the two-level
-- extreme windows and hold checks. Exit status: 0 pass, 1 mismatch, 2 error.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;
use work.stage_bridge_pkg.all;

entity block_filter_tb is
  generic (
    IN_W           : positive := m_width(DEF_M_PROD_W, DEF_M_DROP);  --! M coefficient width
    BF_SUM_W       : positive := DEF_BF_SUM_W;                       --! accumulator width
    BF_DROP        : natural  := DEF_BF_DROP;                        --! LSBs dropped after the sum
    RANDOM_VECTORS : natural  := STAGE_DEF_RANDOM_VECTORS;           --! random vectors after the extremes
    SEED           : natural  := STAGE_DEF_SEED                      --! seed of the C++ generator
  );
end entity block_filter_tb;

architecture sim of block_filter_tb is
  constant OUT_W : positive := bf_width(BF_SUM_W, BF_DROP);   -- packed outputs: sum
  signal clk, rst, en, write : std_logic := '0';
  signal a   : s_matrix3(open)(IN_W - 1 downto 0) := (others => (others => (others => '0')));
  signal sum : signed(OUT_W - 1 downto 0);
begin
  dut : entity work.block_filter
    generic map (IN_W => IN_W, BF_SUM_W => BF_SUM_W, BF_DROP => BF_DROP)
    port map (clk => clk, rst => rst, en => en, write => write, a => a, sum => sum);

  drive : process is
    variable buf : stage_out_buf_t := (others => '0');
    variable rc  : integer;
  begin
    rc := stage_generic(STAGE_G_IN_W, IN_W);
    rc := stage_generic(STAGE_G_BF_SUM_W, BF_SUM_W);
    rc := stage_generic(STAGE_G_BF_DROP, BF_DROP);
    rc := stage_generic(STAGE_G_RANDOM_VECTORS, RANDOM_VECTORS);
    rc := stage_generic(STAGE_G_SEED, SEED);
    if stage_open(STAGE_BLOCK_FILTER, OUT_W) /= 0 then
      std.env.finish(2);
    end if;
    stage_reset(clk, rst);
    while stage_next = 1 loop
      write <= stage_bit(stage_input(0));
      en    <= stage_bit(stage_input(1));
      for k in 0 to 8 loop
        a(k / 3 + 1, k mod 3 + 1) <= to_signed(stage_input(2 + k), IN_W);
      end loop;
      stage_clock(clk);
      buf(0 to OUT_W - 1) := std_ulogic_vector(sum);
      exit when stage_check(buf) /= 0;
    end loop;
    std.env.finish(stage_close);
    wait;
  end process drive;
end architecture sim;
