-- sobel_x: horizontal Sobel gradient of one 3x3 pixel neighbourhood, registered.
--
-- Purpose: ix = [-1 0 +1; -2 0 +2; -1 0 +1] * a. Each pixel is widened to 9 (or, doubled,
-- 10) bits signed, then all six terms are resized to SOBEL_W and added (thesis D.h).
-- With SOBEL_W = 11 the range +-1020 fits exactly (appendix A).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity sobel_x is
  generic (
    SOBEL_W : positive := DEF_SOBEL_W   --! gradient width, signed
  );
  port (
    clk   : in  std_logic;
    rst   : in  std_logic;                        --! active low, asynchronous
    en    : in  std_logic;                        --! register enable (ready)
    write : in  std_logic;                        --! one bus write = one step
    a     : in  u8_matrix3;                       --! 3x3 neighbourhood
    ix    : out signed(SOBEL_W - 1 downto 0)      --! gradient, registered
  );
end entity sobel_x;

architecture rtl of sobel_x is
  signal p11, p13, p31, p33 : signed(PIXEL_W downto 0);      -- +-pixel: 9 bits
  signal p21, p23           : signed(PIXEL_W + 1 downto 0);  -- +-2*pixel: 10 bits
  signal ix_next            : signed(SOBEL_W - 1 downto 0);
begin
  p11 <= -signed(resize(a(1, 1), PIXEL_W + 1));
  p21 <= -signed(resize(a(2, 1), PIXEL_W + 2)) - signed(resize(a(2, 1), PIXEL_W + 2));
  p31 <= -signed(resize(a(3, 1), PIXEL_W + 1));
  p13 <= signed(resize(a(1, 3), PIXEL_W + 1));
  p23 <= signed(resize(a(2, 3), PIXEL_W + 2)) + signed(resize(a(2, 3), PIXEL_W + 2));
  p33 <= signed(resize(a(3, 3), PIXEL_W + 1));
  ix_next <= resize(p11, SOBEL_W) + resize(p13, SOBEL_W) + resize(p21, SOBEL_W)
           + resize(p23, SOBEL_W) + resize(p31, SOBEL_W) + resize(p33, SOBEL_W);

  reg : process (clk, rst) is
  begin
    if rst = '0' then
      ix <= to_signed(0, SOBEL_W);
    elsif clk'event and clk = '1' then
      if write = '1' and en = '1' then
        ix <= ix_next;
      end if;
    end if;
  end process reg;
end architecture rtl;
