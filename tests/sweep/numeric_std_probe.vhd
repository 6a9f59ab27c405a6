-- numeric_std_probe: one output per numeric_std construct of rtl/*.vhd (and shift_right of
-- a signed value, which rtl/ does not use), each a function of the inputs alone, so that
-- GHDL's simulation of it and GHDL's synthesis of it (through yosys) can be compared value
-- by value (tests/sweep/numeric_std_synth_test.cpp).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity numeric_std_probe is
  port (
    x, y         : in  signed(7 downto 0);
    u            : in  unsigned(7 downto 0);
    shrink       : out signed(3 downto 0);    -- resize of a signed value to fewer bits
    slice_shrink : out signed(3 downto 0);    -- resize of a signed slice to fewer bits
    extend       : out signed(11 downto 0);   -- resize of a signed value to more bits
    slice_extend : out signed(7 downto 0);    -- resize of a signed slice to more bits
    u_extend     : out unsigned(11 downto 0); -- resize of an unsigned value to more bits
    neg          : out signed(8 downto 0);    -- -signed(resize(unsigned)), as the Sobel stages
    prod         : out signed(15 downto 0);   -- signed * signed, full width
    sum, diff    : out signed(7 downto 0);    -- wrapping + and -
    gt, ge       : out std_logic;             -- signed > and >=
    shr          : out signed(7 downto 0)     -- shift_right of a signed value
  );
end entity numeric_std_probe;

architecture rtl of numeric_std_probe is
begin
  shrink       <= resize(x, 4);
  slice_shrink <= resize(x(7 downto 1), 4);
  extend       <= resize(x, 12);
  slice_extend <= resize(x(7 downto 2), 8);
  u_extend     <= resize(u, 12);
  neg          <= -signed(resize(u, 9));
  prod         <= x * y;
  sum          <= x + y;
  diff         <= x - y;
  gt           <= '1' when x > y else '0';
  ge           <= '1' when x >= y else '0';
  shr          <= shift_right(x, 2);
end architecture rtl;
