-- load_control: raises `load` while the 7x7 windows are being filled at the start of a row.
--
-- Purpose: counts bus writes within a row of windows (j, 1 .. (w/2+3)*7) and rows within a
-- frame (i, 1 .. h/2-3). `load` is '1' after writes 1..48 of a row and after the last write
-- of every row but the last one of a frame; it is '0' from write 49 (the 7th column is
-- complete) to the end of the row. At the end of a frame's last row `load` is NOT raised:
-- the next frame's first row enters the pipeline from its first column (thesis D.d; kept).
-- Steps only on a clock edge with write = '1'. Reset (active low) is asynchronous.
library ieee;
use ieee.std_logic_1164.all;
use work.harris_pkg.all;

entity load_control is
  generic (
    IMG_WIDTH  : positive := DEF_IMG_WIDTH;   --! image width the counters are built for
    IMG_HEIGHT : positive := DEF_IMG_HEIGHT   --! image height the counters are built for
  );
  port (
    clk   : in  std_logic;
    write : in  std_logic;   --! one bus write = one step
    rst   : in  std_logic;   --! active low, asynchronous
    load  : out std_logic    --! '1' while the window is (re)filled
  );
end entity load_control;

architecture rtl of load_control is
  constant ROW_WRITES : positive := (IMG_WIDTH / 2 + 3) * 7;  -- 7 writes per window column
  constant ROWS       : positive := IMG_HEIGHT / 2 - 3;
  constant FILL       : positive := 49;                        -- 7 columns of 7 rows
  signal row   : integer range 1 to ROWS       := 1;
  signal col   : integer range 1 to ROW_WRITES := 1;
  signal load_r : std_logic := '1';
begin
  count : process (clk, rst) is
  begin
    if rst = '0' then
      row    <= 1;
      col    <= 1;
      load_r <= '1';
    elsif clk'event and clk = '1' then
      if write = '1' then
        if col < ROW_WRITES then
          if col < FILL then
            load_r <= '1';
          else
            load_r <= '0';
          end if;
          col <= col + 1;
        else
          col <= 1;
          if row < ROWS then
            load_r <= '1';
            row    <= row + 1;
          else
            row <= 1;        -- frame end: load stays '0' (thesis behaviour)
          end if;
        end if;
      end if;
    end if;
  end process count;

  load <= load_r;
end architecture rtl;
