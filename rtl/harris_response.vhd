-- harris_response: R = det(M) - k*tr(M)^2 = a*c - b*b - k*(a+c)^2, in two register steps.
--
-- Purpose: step 1 (en0 = t(2)) registers the products a*c, b*b (2*BF_W bits each) and the
-- k-term; step 2 (en1 = t(3)) registers r = ac - bb - ktr2 in RESP_W bits, wrapping.
-- k = 2^-K_SHIFT1 + 2^-K_SHIFT2 (thesis: 1/32 + 1/128 = 0.0390625): (a+c)^2 is cut to its bits
-- above K_SHIFT1 and above K_SHIFT2 (floor of each quotient), each resized to KTR_W bits,
-- and the two are added in KTR_W bits (thesis 5.2.7, D.l).
-- Kept from the thesis: the step-1 registers have no reset ('U' until the first t(2)).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity harris_response is
  generic (
    BF_W     : positive := bf_width(DEF_BF_SUM_W, DEF_BF_DROP);  --! block sum width
    RESP_W   : positive := DEF_RESP_W;                           --! response width
    KTR_W    : positive := DEF_KTR_W;                            --! k*tr^2 width
    K_SHIFT1 : natural  := DEF_K_SHIFT1;                         --! k = 2^-K_SHIFT1 + ...
    K_SHIFT2 : natural  := DEF_K_SHIFT2                          --! ... + 2^-K_SHIFT2
  );
  port (
    clk     : in  std_logic;
    rst     : in  std_logic;                          --! active low (step 2 only)
    en0     : in  std_logic;                          --! t(2): products and k-term
    en1     : in  std_logic;                          --! t(3): response
    write   : in  std_logic;                          --! one write = one step
    a, b, c : in  signed(BF_W - 1 downto 0);          --! filtered M coefficients
    r       : out signed(RESP_W - 1 downto 0)         --! response, registered
  );
end entity harris_response;

architecture rtl of harris_response is
  constant PROD_W : positive := 2 * BF_W;          -- a*c and b*b, full precision
  constant TR_W   : positive := BF_W + 1;          -- a + c
  constant TR2_W  : positive := 2 * TR_W;          -- (a + c)^2
  signal ac_next, bb_next : signed(PROD_W - 1 downto 0);
  signal ac, bb           : signed(PROD_W - 1 downto 0);
  signal trace            : signed(TR_W - 1 downto 0);
  signal trace_sq         : signed(TR2_W - 1 downto 0);
  signal ktr2_next, ktr2  : signed(KTR_W - 1 downto 0);
  signal r_next           : signed(RESP_W - 1 downto 0);
begin
  ac_next  <= a * c;
  bb_next  <= b * b;
  trace    <= resize(a, TR_W) + resize(c, TR_W);
  trace_sq <= trace * trace;
  -- k*tr^2 = floor(tr^2 / 2^K_SHIFT1) + floor(tr^2 / 2^K_SHIFT2), each slice sign-kept
  ktr2_next <= resize(trace_sq(TR2_W - 1 downto K_SHIFT1), KTR_W)
             + resize(trace_sq(TR2_W - 1 downto K_SHIFT2), KTR_W);
  r_next <= resize(ac, RESP_W) - resize(bb, RESP_W) - resize(ktr2, RESP_W);

  step1 : process (clk) is
  begin
    if clk'event and clk = '1' then
      if write = '1' and en0 = '1' then
        ac   <= ac_next;
        bb   <= bb_next;
        ktr2 <= ktr2_next;
      end if;
    end if;
  end process step1;

  step2 : process (clk, rst) is
  begin
    if rst = '0' then
      r <= to_signed(0, RESP_W);
    elsif clk'event and clk = '1' then
      if write = '1' and en1 = '1' then
        r <= r_next;
      end if;
    end if;
  end process step2;
end architecture rtl;
