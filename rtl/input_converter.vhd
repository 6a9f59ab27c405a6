-- input_converter: builds one 7x7 pixel window from a stream of single pixels.
--
-- Purpose: on each write, row `i` of the window shifts one place left and the new pixel
-- enters its rightmost column. Seven writes (i = 1..7) therefore add one column and slide
-- the window one pixel to the right (thesis 5.2.3, D.f). Reset clears the window to zeros.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity input_converter is
  port (
    clk   : in  std_logic;
    rst   : in  std_logic;                              --! active low, asynchronous
    write : in  std_logic;                              --! one bus write = one step
    i     : in  integer range 1 to 7;                   --! window row the pixel belongs to
    data  : in  std_logic_vector(PIXEL_W - 1 downto 0); --! the pixel
    a     : out u8_matrix7                              --! the window
  );
end entity input_converter;

architecture rtl of input_converter is
  signal win : u8_matrix7;
begin
  shift : process (clk, rst) is
  begin
    if rst = '0' then
      win <= (others => (others => (others => '0')));
    elsif clk'event and clk = '1' then
      if write = '1' then
        for col in 1 to 6 loop
          win(i, col) <= win(i, col + 1);
        end loop;
        win(i, 7) <= unsigned(data);
      end if;
    end if;
  end process shift;

  a <= win;
end architecture rtl;
