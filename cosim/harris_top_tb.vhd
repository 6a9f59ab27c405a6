-- harris_top_tb: co-simulation testbench of harris_top, driven write by write from C++.
--
-- Purpose: the C++ bridge (cosim/hc_bridge.h) chooses every bus cycle: a write of a data
-- word or an idle cycle (write = '0'). After each clock edge the testbench hands the whole
-- observation port to C++, which compares it with the cycle model and says whether to go
-- on. Generics are the design's, passed at run time (-gNAME=VALUE); hc_open checks them
-- against the C++ configuration. The exit status is the bridge's: 0 pass, 1 mismatch,
-- 2 error.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;
use work.hc_bridge_pkg.all;

entity harris_top_tb is
  generic (
    IMG_WIDTH  : positive := DEF_IMG_WIDTH;
    IMG_HEIGHT : positive := DEF_IMG_HEIGHT;
    SOBEL_W    : positive := DEF_SOBEL_W;
    M_PROD_W   : positive := DEF_M_PROD_W;
    M_DROP     : natural  := DEF_M_DROP;
    BF_SUM_W   : positive := DEF_BF_SUM_W;
    BF_DROP    : natural  := DEF_BF_DROP;
    RESP_W     : positive := DEF_RESP_W;
    KTR_W      : positive := DEF_KTR_W;
    K_SHIFT1   : natural  := DEF_K_SHIFT1;
    K_SHIFT2   : natural  := DEF_K_SHIFT2;
    THR_SHIFT1 : natural  := DEF_THR_SHIFT1;
    THR_SHIFT2 : natural  := DEF_THR_SHIFT2
  );
end entity harris_top_tb;

architecture sim of harris_top_tb is
  constant OBS_W : positive := obs_width(SOBEL_W, m_width(M_PROD_W, M_DROP),
                                         bf_width(BF_SUM_W, BF_DROP), RESP_W);
  constant HALF  : time := 5 ns;
  signal clk    : std_logic := '0';
  signal rst    : std_logic := '0';
  signal write  : std_logic := '0';
  signal data   : std_logic_vector(31 downto 0) := (others => '0');
  signal corner : std_logic_vector(31 downto 0);
  signal obs    : std_ulogic_vector(0 to OBS_W - 1);
begin
  dut : entity work.harris_top
    generic map (IMG_WIDTH => IMG_WIDTH, IMG_HEIGHT => IMG_HEIGHT, SOBEL_W => SOBEL_W,
                 M_PROD_W => M_PROD_W, M_DROP => M_DROP, BF_SUM_W => BF_SUM_W,
                 BF_DROP => BF_DROP, RESP_W => RESP_W, KTR_W => KTR_W,
                 K_SHIFT1 => K_SHIFT1, K_SHIFT2 => K_SHIFT2,
                 THR_SHIFT1 => THR_SHIFT1, THR_SHIFT2 => THR_SHIFT2, OBSERVE => true)
    port map (clk => clk, rst => rst, write => write, data => data, corner => corner,
              obs => obs);

  drive : process is
    variable buf : hc_obs_buf_t := (others => '0');
    variable cmd : integer;
    variable rc  : integer;
    type int_list is array (natural range <>) of integer;
    constant GENERICS : int_list := (IMG_WIDTH, IMG_HEIGHT, SOBEL_W, M_PROD_W, M_DROP, BF_SUM_W,
                                     BF_DROP, RESP_W, KTR_W, K_SHIFT1, K_SHIFT2, THR_SHIFT1,
                                     THR_SHIFT2);
  begin
    assert OBS_W <= HC_OBS_MAX
      report "observation port of " & integer'image(OBS_W) & " bits exceeds the bridge buffer"
      severity failure;
    for k in GENERICS'range loop
      rc := hc_generic(k, GENERICS(k));
    end loop;
    rc := hc_open(OBS_W);
    if rc /= 0 then
      std.env.finish(2);
    end if;
    -- one clock edge in reset (rst is active low and asynchronous), then release
    wait for HALF;
    clk <= '1';
    wait for HALF;
    clk <= '0';
    rst <= '1';
    loop
      cmd := hc_next;
      exit when cmd = HC_CMD_END;
      if cmd = HC_CMD_WRITE then
        write <= '1';
        data  <= std_logic_vector(to_signed(hc_data, 32));
      else
        write <= '0';
      end if;
      wait for HALF;                 -- inputs settle while the clock is low
      clk <= '1';
      wait for HALF;                 -- the edge and every delta after it
      buf(0 to OBS_W - 1) := obs;
      rc := hc_observe(buf);
      clk <= '0';
      exit when rc /= 0;
    end loop;
    std.env.finish(hc_close);
    wait;
  end process drive;
end architecture sim;
