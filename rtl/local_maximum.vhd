-- local_maximum: non-maximum suppression over a 3x3 neighbourhood (combinational).
--
-- Purpose: corner = '1' when the centre is strictly greater than each of its 8 neighbours.
-- Ties therefore suppress both pixels, and an all-zero neighbourhood gives no corner
-- (thesis 5.2.10, D.o).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity local_maximum is
  generic (
    RESP_W : positive := DEF_RESP_W   --! response width
  );
  port (
    r      : in  s_matrix3(open)(RESP_W - 1 downto 0);   --! thresholded responses
    corner : out std_logic                               --! centre is a strict maximum
  );
end entity local_maximum;

architecture rtl of local_maximum is
begin
  corner <= '1' when r(2, 2) > r(1, 1) and r(2, 2) > r(1, 2) and r(2, 2) > r(1, 3)
                 and r(2, 2) > r(2, 1) and r(2, 2) > r(2, 3)
                 and r(2, 2) > r(3, 1) and r(2, 2) > r(3, 2) and r(2, 2) > r(3, 3)
            else '0';
end architecture rtl;
