-- block_filter: 3x3 box sum of one M coefficient, registered.
--
-- Purpose: the nine inputs are resized to BF_SUM_W bits (sign-extended) and added, then
-- BF_DROP least significant bits are dropped: floor(sum / 2^BF_DROP) (thesis: 20 -> 16 bits,
-- floor(sum / 16)). OpenCV averages (/9); the hardware divides by 2^BF_DROP, a constant
-- scale the threshold absorbs
-- (thesis 5.2.6, D.k).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity block_filter is
  generic (
    IN_W     : positive := m_width(DEF_M_PROD_W, DEF_M_DROP);  --! M coefficient width
    BF_SUM_W : positive := DEF_BF_SUM_W;                       --! accumulator width
    BF_DROP  : natural  := DEF_BF_DROP                         --! LSBs dropped after the sum
  );
  port (
    clk   : in  std_logic;
    rst   : in  std_logic;                                          --! active low
    en    : in  std_logic;                                          --! t(1)
    write : in  std_logic;                                          --! one write = one step
    a     : in  s_matrix3(open)(IN_W - 1 downto 0);                 --! 3x3 neighbourhood
    sum   : out signed(bf_width(BF_SUM_W, BF_DROP) - 1 downto 0)    --! box sum / 2^BF_DROP
  );
end entity block_filter;

architecture rtl of block_filter is
  signal sum_full : signed(BF_SUM_W - 1 downto 0);
begin
  sum_full <= resize(a(1, 1), BF_SUM_W) + resize(a(1, 2), BF_SUM_W) + resize(a(1, 3), BF_SUM_W)
            + resize(a(2, 1), BF_SUM_W) + resize(a(2, 2), BF_SUM_W) + resize(a(2, 3), BF_SUM_W)
            + resize(a(3, 1), BF_SUM_W) + resize(a(3, 2), BF_SUM_W) + resize(a(3, 3), BF_SUM_W);

  reg : process (clk, rst) is
  begin
    if rst = '0' then
      sum <= to_signed(0, bf_width(BF_SUM_W, BF_DROP));
    elsif clk'event and clk = '1' then
      if write = '1' and en = '1' then
        sum <= sum_full(BF_SUM_W - 1 downto BF_DROP);   -- drop BF_DROP LSBs: floor(/2^BF_DROP)
      end if;
    end if;
  end process reg;
end architecture rtl;
