-- harris_top_obs_open: harris_top with its observation port driven (OBSERVE => true) but
-- left open, for tests/cosim/obs_port_synthesis.sh: its synthesis must equal that of
-- harris_top with OBSERVE => false, i.e. the port adds no logic and changes none.
library ieee;
use ieee.std_logic_1164.all;
use work.harris_pkg.all;

entity harris_top_obs_open is
  port (
    clk, rst, write : in  std_logic;
    data            : in  std_logic_vector(31 downto 0);
    corner          : out std_logic_vector(31 downto 0)
  );
end entity harris_top_obs_open;

architecture wrap of harris_top_obs_open is
begin
  dut : entity work.harris_top
    generic map (IMG_WIDTH => 40, IMG_HEIGHT => 30, OBSERVE => true)
    port map (clk => clk, rst => rst, write => write, data => data, corner => corner, obs => open);
end architecture wrap;
