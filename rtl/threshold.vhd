-- threshold: zeroes one response that is below the adaptive threshold, registered.
--
-- Purpose: the response is first delayed by one write (every write, enabled or not) so
-- that it lines up with t(5); on an enabled write the output register takes the delayed
-- response if it is >= thr, else 0; on any other write it takes 0. The output is
-- therefore valid for one write after each enabled write (thesis 5.2.9, D.n, repaired:
-- see docs/rtl-reconstruction.md).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity threshold is
  generic (
    RESP_W : positive := DEF_RESP_W   --! response width
  );
  port (
    clk   : in  std_logic;
    rst   : in  std_logic;                     --! active low, asynchronous
    en    : in  std_logic;                     --! t(5)
    write : in  std_logic;                     --! one write = one step
    r0    : in  signed(RESP_W - 1 downto 0);   --! response
    thr   : in  signed(RESP_W - 1 downto 0);   --! threshold from the previous maximum
    r1    : out signed(RESP_W - 1 downto 0)    --! thresholded response, registered
  );
end entity threshold;

architecture rtl of threshold is
  signal r0_delay : signed(RESP_W - 1 downto 0);
  signal r1_next  : signed(RESP_W - 1 downto 0);
begin
  r1_next <= r0_delay when r0_delay >= thr else to_signed(0, RESP_W);

  reg : process (clk, rst) is
  begin
    if rst = '0' then
      r0_delay <= to_signed(0, RESP_W);
      r1       <= to_signed(0, RESP_W);
    elsif clk'event and clk = '1' then
      if write = '1' then
        r0_delay <= r0;
        if en = '1' then
          r1 <= r1_next;
        else
          r1 <= to_signed(0, RESP_W);
        end if;
      end if;
    end if;
  end process reg;
end architecture rtl;
