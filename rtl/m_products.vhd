-- m_products: the three coefficients of the Harris matrix M for one pixel, registered.
--
-- Purpose: a = ix*ix, b = ix*iy, c = iy*iy (Harris & Stephens 1988). Each full product
-- (2*SOBEL_W bits) is resized with numeric_std semantics to M_PROD_W bits (sign kept, high
-- bits dropped; exact for |ix|,|iy| <= 1020 since 1020^2 < 2^20), then its M_DROP least
-- significant bits are dropped: floor(x / 2^M_DROP) in M_PROD_W - M_DROP bits (thesis:
-- 21 -> 16 bits, floor(x / 32); 5.2.5, D.j).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity m_products is
  generic (
    SOBEL_W  : positive := DEF_SOBEL_W;    --! gradient width, signed
    M_PROD_W : positive := DEF_M_PROD_W;   --! product width before the cut
    M_DROP   : natural  := DEF_M_DROP      --! LSBs dropped after the product
  );
  port (
    clk     : in  std_logic;
    rst     : in  std_logic;                                        --! active low
    en      : in  std_logic;                                        --! t(0)
    write   : in  std_logic;                                        --! one write = one step
    ix, iy  : in  signed(SOBEL_W - 1 downto 0);                     --! gradients
    a, b, c : out signed(m_width(M_PROD_W, M_DROP) - 1 downto 0)    --! ix*ix, ix*iy, iy*iy
  );
end entity m_products;

architecture rtl of m_products is
  constant M_W : positive := m_width(M_PROD_W, M_DROP);
  signal a_full, b_full, c_full : signed(M_PROD_W - 1 downto 0);
begin
  a_full <= resize(ix * ix, M_PROD_W);
  b_full <= resize(ix * iy, M_PROD_W);
  c_full <= resize(iy * iy, M_PROD_W);

  reg : process (clk, rst) is
  begin
    if rst = '0' then
      a <= to_signed(0, M_W);
      b <= to_signed(0, M_W);
      c <= to_signed(0, M_W);
    elsif clk'event and clk = '1' then
      if write = '1' and en = '1' then
        -- drop M_DROP LSBs: division by 2^M_DROP rounding towards minus infinity
        a <= a_full(M_PROD_W - 1 downto M_DROP);
        b <= b_full(M_PROD_W - 1 downto M_DROP);
        c <= c_full(M_PROD_W - 1 downto M_DROP);
      end if;
    end if;
  end process reg;
end architecture rtl;
