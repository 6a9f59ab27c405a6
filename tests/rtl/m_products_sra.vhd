-- m_products_sra: TEST-ONLY variant of rtl/m_products.vhd (same entity name, same ports)
-- that sign-extends the gradient ix with an arithmetic shift instead of resize().
--
-- Purpose: in VHDL the two forms are the same function. For signed ix of SOBEL_W bits,
--   shift_right(ix & '0', 1)  ==  resize(ix, SOBEL_W + 1)
-- because shift_right on `signed` replicates the sign bit. The cycle model, and GHDL's
-- simulation of this file, therefore agree with rtl/m_products.vhd bit for bit. GHDL 2.0's
-- `--synth --out=verilog` however writes shift_right on signed as
--   assign n = $signed({ix, 1'b0}) >> 1;
-- and Verilog's `>>` is a logical shift (the arithmetic one is `>>>`): the top bit of the
-- widened ix becomes '0', so a negative ix turns into ix + 2^SOBEL_W and b = ix*iy is wrong
-- whenever ix < 0 and iy /= 0. The Verilator gate (tests/verilator) must report that as a
-- translation fault (GHDL != Verilator while GHDL == model), not as an RTL fault.
--
-- Why this form: a shift whose filled-in bits are dropped afterwards (e.g.
-- resize(shift_right(b_full, M_DROP), M_W)) does not show the defect, because GHDL then
-- truncates and the wrong fill bits never reach an output. The widened ix keeps its top
-- bit. a and c keep the rtl/ form so that only b carries the defect.
--
-- Never analysed for the real design: tests/verilator substitutes it for
-- rtl/m_products.vhd (harris-cosim verilate --variant).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity m_products is
  generic (
    SOBEL_W  : positive := DEF_SOBEL_W;    --! gradient width, signed
    M_PROD_W : positive := DEF_M_PROD_W;   --! product width before the cut
    M_DROP   : natural  := DEF_M_DROP      --! LSBs dropped after the product
  );
  port (
    clk     : in  std_logic;
    rst     : in  std_logic;                                        --! active low
    en      : in  std_logic;                                        --! t(0)
    write   : in  std_logic;                                        --! one write = one step
    ix, iy  : in  signed(SOBEL_W - 1 downto 0);                     --! gradients
    a, b, c : out signed(m_width(M_PROD_W, M_DROP) - 1 downto 0)    --! ix*ix, ix*iy, iy*iy
  );
end entity m_products;

architecture rtl of m_products is
  constant M_W : positive := m_width(M_PROD_W, M_DROP);
  signal a_full, b_full, c_full : signed(M_PROD_W - 1 downto 0);
  signal ix_ext                 : signed(SOBEL_W downto 0);   -- ix, one bit wider
begin
  -- resize(ix, SOBEL_W + 1) written as an arithmetic shift: the form the translator gets wrong
  ix_ext <= shift_right(ix & '0', 1);
  a_full <= resize(ix * ix, M_PROD_W);
  b_full <= resize(ix_ext * iy, M_PROD_W);
  c_full <= resize(iy * iy, M_PROD_W);

  reg : process (clk, rst) is
  begin
    if rst = '0' then
      a <= to_signed(0, M_W);
      b <= to_signed(0, M_W);
      c <= to_signed(0, M_W);
    elsif clk'event and clk = '1' then
      if write = '1' and en = '1' then
        -- drop M_DROP LSBs: division by 2^M_DROP rounding towards minus infinity
        a <= a_full(M_PROD_W - 1 downto M_DROP);
        b <= b_full(M_PROD_W - 1 downto M_DROP);
        c <= c_full(M_PROD_W - 1 downto M_DROP);
      end if;
    end if;
  end process reg;
end architecture rtl;
