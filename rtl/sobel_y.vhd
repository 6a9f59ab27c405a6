-- sobel_y: vertical Sobel gradient of one 3x3 pixel neighbourhood, registered.
--
-- Purpose: iy = [+1 +2 +1; 0 0 0; -1 -2 -1] * a, i.e. top row minus bottom row, the
-- opposite sign of thesis eq. (5.1) and of OpenCV's dy; the design only uses iy in ix*iy
-- and iy*iy, and the response only squares ix*iy, so the sign does not reach a corner
-- (thesis D.i, whose comment shows this kernel).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity sobel_y is
  generic (
    SOBEL_W : positive := DEF_SOBEL_W   --! gradient width, signed
  );
  port (
    clk   : in  std_logic;
    rst   : in  std_logic;                        --! active low, asynchronous
    en    : in  std_logic;                        --! register enable (ready)
    write : in  std_logic;                        --! one bus write = one step
    a     : in  u8_matrix3;                       --! 3x3 neighbourhood
    iy    : out signed(SOBEL_W - 1 downto 0)      --! gradient, registered
  );
end entity sobel_y;

architecture rtl of sobel_y is
  signal p11, p13, p31, p33 : signed(PIXEL_W downto 0);      -- +-pixel: 9 bits
  signal p12, p32           : signed(PIXEL_W + 1 downto 0);  -- +-2*pixel: 10 bits
  signal iy_next            : signed(SOBEL_W - 1 downto 0);
begin
  p11 <= signed(resize(a(1, 1), PIXEL_W + 1));
  p12 <= signed(resize(a(1, 2), PIXEL_W + 2)) + signed(resize(a(1, 2), PIXEL_W + 2));
  p13 <= signed(resize(a(1, 3), PIXEL_W + 1));
  p31 <= -signed(resize(a(3, 1), PIXEL_W + 1));
  p32 <= -signed(resize(a(3, 2), PIXEL_W + 2)) - signed(resize(a(3, 2), PIXEL_W + 2));
  p33 <= -signed(resize(a(3, 3), PIXEL_W + 1));
  iy_next <= resize(p11, SOBEL_W) + resize(p12, SOBEL_W) + resize(p13, SOBEL_W)
           + resize(p31, SOBEL_W) + resize(p32, SOBEL_W) + resize(p33, SOBEL_W);

  reg : process (clk, rst) is
  begin
    if rst = '0' then
      iy <= to_signed(0, SOBEL_W);
    elsif clk'event and clk = '1' then
      if write = '1' and en = '1' then
        iy <= iy_next;
      end if;
    end if;
  end process reg;
end architecture rtl;
