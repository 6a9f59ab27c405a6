-- ghdl_replay_tb: replays a recorded bus-write stream into harris_top under GHDL and
-- records what the host could read after every write, for the Verilator gate.
--
-- Purpose: the GHDL leg of the three-way gate (GHDL / Verilator / model, see
-- docs/verilator.md). It simulates the VHDL sources themselves, so it is the reference
-- the Verilog translation is held against. Plain textio, no foreign calls, so it does not
-- depend on the VHPIDIRECT co-simulation.
--
-- STIM: one 32-bit data word per line, 8 hex digits, in bus order (written by
-- hc::vl::write_stimulus from hc::HostDriver).
-- RESULT: one line per write, after its clock edge: the corner port as 8 hex digits,
-- then, when OBSERVE, a space and obs(0 to N-1) as characters of std_ulogic ('0', '1',
-- 'U', ...), index 0 first.
-- Stepping: rst is pulsed low once before the first write; each write is one rising
-- edge with write = '1', as in the thesis's bus interface.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use std.textio.all;
use work.harris_pkg.all;

entity ghdl_replay_tb is
  generic (
    STIM       : string   := "stim.txt";
    RESULT     : string   := "result.txt";
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
    THR_SHIFT2 : natural  := DEF_THR_SHIFT2;
    OBSERVE    : boolean  := true
  );
end entity ghdl_replay_tb;

architecture sim of ghdl_replay_tb is
  constant OBS_N : positive := sel_width(OBSERVE,
      obs_width(SOBEL_W, m_width(M_PROD_W, M_DROP), bf_width(BF_SUM_W, BF_DROP), RESP_W));
  signal clk, write : std_logic := '0';
  signal rst        : std_logic := '1';
  signal data       : std_logic_vector(31 downto 0) := (others => '0');
  signal corner     : std_logic_vector(31 downto 0);
  signal obs        : std_ulogic_vector(0 to OBS_N - 1);
begin
  dut : entity work.harris_top
    generic map (
      IMG_WIDTH => IMG_WIDTH, IMG_HEIGHT => IMG_HEIGHT, SOBEL_W => SOBEL_W,
      M_PROD_W => M_PROD_W, M_DROP => M_DROP, BF_SUM_W => BF_SUM_W, BF_DROP => BF_DROP,
      RESP_W => RESP_W, KTR_W => KTR_W, K_SHIFT1 => K_SHIFT1, K_SHIFT2 => K_SHIFT2,
      THR_SHIFT1 => THR_SHIFT1, THR_SHIFT2 => THR_SHIFT2, OBSERVE => OBSERVE)
    port map (clk => clk, rst => rst, write => write, data => data, corner => corner,
              obs => obs);

  replay : process is
    file stim_f   : text open read_mode is STIM;
    file result_f : text open write_mode is RESULT;
    variable li, lo : line;
    variable w      : std_logic_vector(31 downto 0);
  begin
    rst <= '0';
    wait for 5 ns;
    rst <= '1';
    wait for 5 ns;
    while not endfile(stim_f) loop
      readline(stim_f, li);
      hread(li, w);
      data  <= w;
      write <= '1';
      wait for 5 ns;
      clk <= '1';                 -- the write's rising edge
      wait for 5 ns;
      clk   <= '0';
      write <= '0';
      wait for 1 ns;              -- let the combinational outputs settle
      hwrite(lo, corner);
      if OBSERVE then
        std.textio.write(lo, string'(" "));   -- `write` is the bus strobe here
        for k in obs'range loop
          std.textio.write(lo, std_ulogic'image(obs(k))(2));
        end loop;
      end if;
      writeline(result_f, lo);
      wait for 4 ns;
    end loop;
    std.env.finish;
  end process replay;
end architecture sim;
