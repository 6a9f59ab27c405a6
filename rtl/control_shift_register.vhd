-- control_shift_register: the stage enables of the pipeline.
--
-- Purpose: a 6-bit shift register of `ready`, stepping on every write. Bit k enables the
-- stage k+1 writes behind the Sobel stage: t(0) M products, t(1) block filter, t(2) and
-- t(3) the two halves of the Harris response, t(4) find-max, t(5) threshold (thesis D.g).
library ieee;
use ieee.std_logic_1164.all;

entity control_shift_register is
  port (
    clk   : in  std_logic;
    write : in  std_logic;                     --! one bus write = one step
    rst   : in  std_logic;                     --! active low, asynchronous
    ready : in  std_logic;                     --! from input_converter_mux
    t     : out std_logic_vector(5 downto 0)   --! stage enables
  );
end entity control_shift_register;

architecture rtl of control_shift_register is
  signal tt : std_logic_vector(5 downto 0);
begin
  shift : process (clk, rst) is
  begin
    if rst = '0' then
      tt <= (others => '0');
    elsif clk'event and clk = '1' then
      if write = '1' then
        tt <= tt(4 downto 0) & ready;
      end if;
    end if;
  end process shift;

  t <= tt;
end architecture rtl;
