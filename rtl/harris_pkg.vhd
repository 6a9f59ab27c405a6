-- harris_pkg: formats, matrix types and the observation layout of the Harris co-processor.
--
-- Purpose: every bit width, dropped-bit count and constant shift of the design is declared
-- here once, with the values of Schulz (2015) as defaults (thesis appendix A and D.b). The
-- entities take them as generics whose defaults are these constants. The C++ side owns the
-- list of fields: the table of formats in model/harris/harris_pkg.hpp (names, generics,
-- defaults); tests/model/vhdl_agreement_test.cpp fails when a DEF_* constant here differs
-- from it, and the testbenches' generic lists are generated from the DEF_* constants here.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

package harris_pkg is
  -- Image size the counters are built for (thesis: 640x360 webcam frames).
  constant DEF_IMG_WIDTH  : positive := 640;
  constant DEF_IMG_HEIGHT : positive := 360;

  -- Pixels are 8-bit unsigned: the 32-bit bus carries four of them. Not a generic.
  constant PIXEL_W : positive := 8;

  -- Sobel x/y output: signed, range +-1020 needs 11 bits (appendix A).
  constant DEF_SOBEL_W  : positive := 11;
  -- M products: ix*ix, ix*iy, iy*iy resized to M_PROD_W bits, then M_DROP LSBs dropped.
  constant DEF_M_PROD_W : positive := 21;
  constant DEF_M_DROP   : natural  := 5;
  -- Block filter: nine M values summed in BF_SUM_W bits, then BF_DROP LSBs dropped (not /9).
  constant DEF_BF_SUM_W : positive := 20;
  constant DEF_BF_DROP  : natural  := 4;
  -- Harris response r = a*c - b*b - k*(a+c)^2 in RESP_W bits; the k-term in KTR_W bits.
  constant DEF_RESP_W   : positive := 32;
  constant DEF_KTR_W    : positive := 30;
  -- k = 2^-K_SHIFT1 + 2^-K_SHIFT2 (thesis 0.0390625, OpenCV's 0.04): two shifted (a+c)^2 added.
  constant DEF_K_SHIFT1 : natural  := 5;
  constant DEF_K_SHIFT2 : natural  := 7;
  -- Threshold = max * (2^-THR_SHIFT1 + 2^-THR_SHIFT2) (thesis 0.009765625 * max, OpenCV's 0.01).
  constant DEF_THR_SHIFT1 : natural := 7;
  constant DEF_THR_SHIFT2 : natural := 9;

  -- Window matrices. The pixel window has a fixed element type; the signed matrices are
  -- VHDL-2008 arrays of unconstrained elements whose width each user constrains from generics.
  type u8_matrix7 is array (1 to 7, 1 to 7) of unsigned(PIXEL_W - 1 downto 0);
  type u8_matrix3 is array (1 to 3, 1 to 3) of unsigned(PIXEL_W - 1 downto 0);
  type s_matrix5  is array (1 to 5, 1 to 5) of signed;
  type s_matrix3  is array (1 to 3, 1 to 3) of signed;

  -- Derived widths (do not set these: they follow from the generics above).
  function m_width(m_prod_w : positive; m_drop : natural) return positive;
  function bf_width(bf_sum_w : positive; bf_drop : natural) return positive;

  -- Find-max period: windows the counter expects in one frame, (h/2-3)*(w/2+3)*4.
  function find_max_period(img_width, img_height : positive) return positive;

  -- Observation port: every inter-stage register of harris_top, packed in pipeline order
  -- (see harris_top and model/harris/observation.hpp, which mirrors this layout). Matrices
  -- are row-major from (1,1); each value most significant bit first.
  function obs_width(sobel_w, m_w, bf_w, resp_w : positive) return positive;
  -- width of the observation port: obs_w when observing, else a single constant bit
  function sel_width(observe : boolean; obs_w : positive) return positive;
end package harris_pkg;

package body harris_pkg is
  function m_width(m_prod_w : positive; m_drop : natural) return positive is
  begin
    return m_prod_w - m_drop;
  end function;

  function bf_width(bf_sum_w : positive; bf_drop : natural) return positive is
  begin
    return bf_sum_w - bf_drop;
  end function;

  function find_max_period(img_width, img_height : positive) return positive is
  begin
    return ((img_height / 2 - 3) * (img_width / 2 + 3)) * 4;
  end function;

  function obs_width(sobel_w, m_w, bf_w, resp_w : positive) return positive is
  begin
    return 1 + 1 + 6                -- load, ready, t(5 downto 0)
         + 49 * PIXEL_W             -- window entering the pipeline
         + 2 * 25 * sobel_w         -- sobel x, sobel y
         + 3 * 25 * m_w             -- M a, b, c
         + 3 * 9 * bf_w             -- block sums a, b, c
         + 9 * resp_w               -- responses
         + 2 * resp_w               -- max, thr
         + 9 * resp_w               -- thresholded responses
         + 1 + 4                    -- corner bit, shift register output
         + 32;                      -- the corner port as the host reads it
  end function;

  function sel_width(observe : boolean; obs_w : positive) return positive is
  begin
    if observe then
      return obs_w;
    end if;
    return 1;
  end function;
end package body harris_pkg;
