-- local_maximum_ge: TEST-ONLY variant of rtl/local_maximum.vhd (same entity, same ports)
-- with a deliberate RTL fault: ">=" instead of ">" in the non-maximum suppression.
--
-- Purpose: the opposite of m_products_sra.vhd. Here the VHDL itself disagrees with the
-- cycle model (ties, including an all-zero neighbourhood, now make a corner), while GHDL
-- and the Verilog translation agree with each other. tests/verilator uses it to show that
-- the gate calls this an RTL fault, not a translation fault, and that the lock-step run
-- names the frame, pixel, quadrant and signal of the first mismatch.
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
    corner : out std_logic                               --! centre is a (non-strict) maximum
  );
end entity local_maximum;

architecture rtl of local_maximum is
begin
  -- the fault: >= lets a plateau (e.g. nine thresholded zeros) through as a corner
  corner <= '1' when r(2, 2) >= r(1, 1) and r(2, 2) >= r(1, 2) and r(2, 2) >= r(1, 3)
                 and r(2, 2) >= r(2, 1) and r(2, 2) >= r(2, 3)
                 and r(2, 2) >= r(3, 1) and r(2, 2) >= r(3, 2) and r(2, 2) >= r(3, 3)
            else '0';
end architecture rtl;
