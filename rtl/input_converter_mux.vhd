-- input_converter_mux: four input converters, one per image quadrant, and the multiplexer
-- that feeds their windows to the pipeline one after another.
--
-- Purpose: each 32-bit write carries one pixel of each quadrant (byte q = quadrant q). The
-- row counter `i` (1..7) steps on every write. Converter q sees the byte and the counter
-- delayed by q writes, so its window is complete exactly when the multiplexer selects it:
-- on the write with i = q+1 the output register takes window q (i = 1..4), otherwise zeros.
-- `ready` is '1' while i = 2..5 and load = '0': the four writes on which the window now in
-- the output register is a freshly completed one (thesis 5.2.3, D.e).
-- Kept from the thesis: only `i` is reset; the delayed counters and data, and the output
-- register, keep their power-up values through a reset (the output is 'U' until the first
-- write).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity input_converter_mux is
  port (
    clk   : in  std_logic;
    rst   : in  std_logic;                      --! active low, asynchronous
    write : in  std_logic;                      --! one bus write = one step
    load  : in  std_logic;                      --! from load_control
    data  : in  std_logic_vector(31 downto 0);  --! byte q = pixel of quadrant q
    a     : out u8_matrix7;                     --! window entering the pipeline
    ready : out std_logic                       --! `a` holds a window to process
  );
end entity input_converter_mux;

architecture rtl of input_converter_mux is
  constant ZERO_WINDOW : u8_matrix7 := (others => (others => (others => '0')));
  type row_delay_t  is array (1 to 3) of integer range 1 to 7;
  type data_delay_t is array (1 to 3) of std_logic_vector(31 downto 0);
  type window_set_t is array (0 to 3) of u8_matrix7;
  signal i        : integer range 1 to 7 := 1;
  signal i_dly    : row_delay_t  := (others => 1);
  signal data_dly : data_delay_t := (others => (others => '0'));
  signal win      : window_set_t;
begin
  -- Quadrant 0 takes the write as it comes; quadrant q (1..3) q writes later.
  ic0 : entity work.input_converter
    port map (clk => clk, rst => rst, write => write, i => i,
              data => data(7 downto 0), a => win(0));
  delayed : for q in 1 to 3 generate
    icq : entity work.input_converter
      port map (clk => clk, rst => rst, write => write, i => i_dly(q),
                data => data_dly(q)(8 * q + 7 downto 8 * q), a => win(q));
  end generate delayed;

  select_window : process (clk, rst) is
  begin
    if rst = '0' then
      i <= 1;
    elsif clk'event and clk = '1' then
      if write = '1' then
        if i <= 4 then
          a <= win(i - 1);
        else
          a <= ZERO_WINDOW;
        end if;
        if i < 7 then
          i <= i + 1;
        else
          i <= 1;
        end if;
        i_dly    <= i & i_dly(1 to 2);
        data_dly <= data & data_dly(1 to 2);
      end if;
    end if;
  end process select_window;

  ready <= '1' when (i > 1 and i <= 5 and load = '0') else '0';
end architecture rtl;
