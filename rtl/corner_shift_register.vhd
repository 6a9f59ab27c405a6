-- corner_shift_register: delays the corner bits so the host reads them 14 writes later.
--
-- Purpose: a 6-bit shift register of the corner bit, stepping on every write; the host
-- reads bits 5..2, i.e. the four windows' results (thesis 5.2.11, D.p).
library ieee;
use ieee.std_logic_1164.all;

entity corner_shift_register is
  port (
    clk       : in  std_logic;
    rst       : in  std_logic;                      --! active low, asynchronous
    write     : in  std_logic;                      --! one write = one step
    corner    : in  std_logic;                      --! from local_maximum
    corner_sr : out std_logic_vector(3 downto 0)    --! bits 5..2 of the register
  );
end entity corner_shift_register;

architecture rtl of corner_shift_register is
  signal c : std_logic_vector(5 downto 0);
begin
  shift : process (clk, rst) is
  begin
    if rst = '0' then
      c <= (others => '0');
    elsif clk'event and clk = '1' then
      if write = '1' then
        c <= c(4 downto 0) & corner;
      end if;
    end if;
  end process shift;

  corner_sr <= c(5 downto 2);
end architecture rtl;
