-- numeric_std_probe_tb: GHDL's simulation of numeric_std_probe at the inputs X, Y, U
-- (top-level generics), one line "name=value" per output, values as integers.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity numeric_std_probe_tb is
  generic (X, Y : integer := 0; U : natural := 0);
end entity numeric_std_probe_tb;

architecture sim of numeric_std_probe_tb is
  signal xs, ys                              : signed(7 downto 0) := (others => '0');
  signal sum, diff, slice_extend, shr        : signed(7 downto 0);
  signal us                                  : unsigned(7 downto 0) := (others => '0');
  signal shrink, slice_shrink                : signed(3 downto 0);
  signal extend                              : signed(11 downto 0);
  signal u_extend                            : unsigned(11 downto 0);
  signal neg                                 : signed(8 downto 0);
  signal prod                                : signed(15 downto 0);
  signal gt, ge                              : std_logic;
begin
  dut : entity work.numeric_std_probe
    port map (x => xs, y => ys, u => us, shrink => shrink, slice_shrink => slice_shrink, extend => extend,
              slice_extend => slice_extend, u_extend => u_extend, neg => neg, prod => prod, sum => sum,
              diff => diff, gt => gt, ge => ge, shr => shr);

  run : process is
    procedure put(name : string; v : integer) is
    begin
      report name & "=" & integer'image(v) severity note;
    end procedure put;
  begin
    xs <= to_signed(X, 8);
    ys <= to_signed(Y, 8);
    us <= to_unsigned(U, 8);
    wait for 1 ns;
    put("shrink", to_integer(shrink));
    put("slice_shrink", to_integer(slice_shrink));
    put("extend", to_integer(extend));
    put("slice_extend", to_integer(slice_extend));
    put("u_extend", to_integer(u_extend));
    put("neg", to_integer(neg));
    put("prod", to_integer(prod));
    put("sum", to_integer(sum));
    put("diff", to_integer(diff));
    put("gt", to_integer(unsigned'("" & gt)));
    put("ge", to_integer(unsigned'("" & ge)));
    put("shr", to_integer(shr));
    wait;
  end process run;
end architecture sim;
