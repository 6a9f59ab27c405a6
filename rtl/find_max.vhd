-- find_max: the largest centre response over one period of enabled steps.
--
-- Purpose: on every enabled step (t(4)) the centre response is compared with the running
-- maximum. After find_max_period(w, h) = (h/2-3)*(w/2+3)*4 enabled steps the running
-- maximum is published on `max` and restarts from the most negative value; the response
-- seen on the step that ends a period is not counted (the restart assignment wins).
-- The period assumes every window column is processed, which the pipeline does not do
-- (see load_control), so the published maximum drifts against frame boundaries
-- (thesis 5.2.8, D.m). Kept from the thesis: only `max` is reset; the counter and the
-- running maximum keep their values through a reset.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity find_max is
  generic (
    IMG_WIDTH  : positive := DEF_IMG_WIDTH;    --! image width the period is built for
    IMG_HEIGHT : positive := DEF_IMG_HEIGHT;   --! image height the period is built for
    RESP_W     : positive := DEF_RESP_W        --! response width
  );
  port (
    clk      : in  std_logic;
    rst      : in  std_logic;                        --! active low (max only)
    en       : in  std_logic;                        --! t(4)
    write    : in  std_logic;                        --! one write = one step
    response : in  signed(RESP_W - 1 downto 0);      --! centre response hrm(2,2)
    max      : out signed(RESP_W - 1 downto 0)       --! maximum of the last period
  );
end entity find_max;

architecture rtl of find_max is
  constant PERIOD   : positive := find_max_period(IMG_WIDTH, IMG_HEIGHT);
  constant MOST_NEG : signed(RESP_W - 1 downto 0) := ('1', others => '0');
  signal count   : integer range 1 to PERIOD := 1;
  signal running : signed(RESP_W - 1 downto 0) := MOST_NEG;
begin
  track : process (clk, rst) is
  begin
    if rst = '0' then
      max <= MOST_NEG;
    elsif clk'event and clk = '1' then
      if write = '1' and en = '1' then
        if response > running then
          running <= response;
        end if;
        if count < PERIOD then
          count <= count + 1;
        else
          count   <= 1;
          running <= MOST_NEG;   -- overrides the update above
          max     <= running;
        end if;
      end if;
    end if;
  end process track;
end architecture rtl;
