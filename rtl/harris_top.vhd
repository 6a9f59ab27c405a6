-- harris_top: the Harris corner co-processor (the thesis's `system`, D.c).
--
-- Purpose: wires the stages in pipeline order. One bus write (write = '1' on a rising
-- clock edge) is one step of every register. Each write carries one pixel of each of four
-- image quadrants; after 7 writes per window column the host reads `corner`, whose bits
-- 3..0 are the corner flags of quadrants 0..3 for the window completed two columns before.
--
--   load_control -> input_converter_mux -> sobel_x/sobel_y (en = ready)
--   -> m_products (t0) -> block_filter (t1) -> harris_response (t2, t3)
--   -> find_max (t4) -> threshold (t5) -> local_maximum -> corner_shift_register
--
-- The observation port `obs` exposes every inter-stage register for co-simulation (GHDL
-- 2.0 has no VHDL-2008 external names). It only reads signals, so it cannot change the
-- design's behaviour; with OBSERVE = false it is a single constant bit, and a synthesis of
-- either variant with `obs` left open is the same circuit (tests/cosim/obs_port_synthesis.sh).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use work.harris_pkg.all;

entity harris_top is
  generic (
    IMG_WIDTH  : positive := DEF_IMG_WIDTH;    --! image width (counters)
    IMG_HEIGHT : positive := DEF_IMG_HEIGHT;   --! image height (counters)
    SOBEL_W    : positive := DEF_SOBEL_W;      --! Sobel output width
    M_PROD_W   : positive := DEF_M_PROD_W;     --! M product width before the cut
    M_DROP     : natural  := DEF_M_DROP;       --! LSBs dropped from M products
    BF_SUM_W   : positive := DEF_BF_SUM_W;     --! block-sum accumulator width
    BF_DROP    : natural  := DEF_BF_DROP;      --! LSBs dropped from block sums
    RESP_W     : positive := DEF_RESP_W;       --! response, maximum, threshold width
    KTR_W      : positive := DEF_KTR_W;        --! k*tr^2 width
    K_SHIFT1   : natural  := DEF_K_SHIFT1;     --! k = 2^-K_SHIFT1 + 2^-K_SHIFT2
    K_SHIFT2   : natural  := DEF_K_SHIFT2;
    THR_SHIFT1 : natural  := DEF_THR_SHIFT1;   --! thr = max*(2^-THR_SHIFT1 + 2^-THR_SHIFT2)
    THR_SHIFT2 : natural  := DEF_THR_SHIFT2;
    OBSERVE    : boolean  := true              --! drive the observation port
  );
  port (
    clk    : in  std_logic;
    rst    : in  std_logic;                          --! active low, asynchronous
    write  : in  std_logic;                          --! bus write strobe: one write = one step
    data   : in  std_logic_vector(31 downto 0);      --! 4 pixels: byte q = quadrant q
    corner : out std_logic_vector(31 downto 0);      --! bits 3..0: quadrants 0..3
    obs    : out std_ulogic_vector(0 to sel_width(OBSERVE,
                   obs_width(SOBEL_W, m_width(M_PROD_W, M_DROP),
                             bf_width(BF_SUM_W, BF_DROP), RESP_W)) - 1)  --! observation
  );
end entity harris_top;

architecture rtl of harris_top is
  constant M_W  : positive := m_width(M_PROD_W, M_DROP);
  constant BF_W : positive := bf_width(BF_SUM_W, BF_DROP);

  signal load      : std_logic;
  signal ready     : std_logic;
  signal t         : std_logic_vector(5 downto 0);
  signal icm       : u8_matrix7;
  signal sxm, sym  : s_matrix5(open)(SOBEL_W - 1 downto 0);
  signal mam, mbm, mcm    : s_matrix5(open)(M_W - 1 downto 0);
  signal bfam, bfbm, bfcm : s_matrix3(open)(BF_W - 1 downto 0);
  signal hrm, trm  : s_matrix3(open)(RESP_W - 1 downto 0);
  signal max, thr  : signed(RESP_W - 1 downto 0);
  signal cornerbit : std_logic;
  signal corner_sr : std_logic_vector(3 downto 0);
  signal corner_o  : std_logic_vector(31 downto 0);

begin
  lc : entity work.load_control
    generic map (IMG_WIDTH => IMG_WIDTH, IMG_HEIGHT => IMG_HEIGHT)
    port map (clk => clk, write => write, rst => rst, load => load);

  icmux : entity work.input_converter_mux
    port map (clk => clk, rst => rst, write => write, load => load, data => data,
              a => icm, ready => ready);

  ctrl : entity work.control_shift_register
    port map (clk => clk, write => write, rst => rst, ready => ready, t => t);

  -- 5x5 gradients and M coefficients: element (i, j) is centred on window pixel (i+1, j+1)
  rows5 : for i in 1 to 5 generate
    cols5 : for j in 1 to 5 generate
      signal nb : u8_matrix3;   -- window pixels (i..i+2, j..j+2)
    begin
      nbr : for di in 1 to 3 generate
        nbc : for dj in 1 to 3 generate
          nb(di, dj) <= icm(i + di - 1, j + dj - 1);
        end generate nbc;
      end generate nbr;
      sx : entity work.sobel_x
        generic map (SOBEL_W => SOBEL_W)
        port map (clk => clk, rst => rst, en => ready, write => write,
                  a => nb, ix => sxm(i, j));
      sy : entity work.sobel_y
        generic map (SOBEL_W => SOBEL_W)
        port map (clk => clk, rst => rst, en => ready, write => write,
                  a => nb, iy => sym(i, j));
      mm : entity work.m_products
        generic map (SOBEL_W => SOBEL_W, M_PROD_W => M_PROD_W, M_DROP => M_DROP)
        port map (clk => clk, rst => rst, en => t(0), write => write,
                  ix => sxm(i, j), iy => sym(i, j),
                  a => mam(i, j), b => mbm(i, j), c => mcm(i, j));
    end generate cols5;
  end generate rows5;

  -- 3x3 block sums, responses and thresholded responses: (i, j) centred on (i+2, j+2)
  rows3 : for i in 1 to 3 generate
    cols3 : for j in 1 to 3 generate
      -- M coefficients (i..i+2, j..j+2)
      signal nba, nbb, nbc : s_matrix3(open)(M_W - 1 downto 0);
    begin
      nbr : for di in 1 to 3 generate
        nbcol : for dj in 1 to 3 generate
          nba(di, dj) <= mam(i + di - 1, j + dj - 1);
          nbb(di, dj) <= mbm(i + di - 1, j + dj - 1);
          nbc(di, dj) <= mcm(i + di - 1, j + dj - 1);
        end generate nbcol;
      end generate nbr;
      bfa : entity work.block_filter
        generic map (IN_W => M_W, BF_SUM_W => BF_SUM_W, BF_DROP => BF_DROP)
        port map (clk => clk, rst => rst, en => t(1), write => write,
                  a => nba, sum => bfam(i, j));
      bfb : entity work.block_filter
        generic map (IN_W => M_W, BF_SUM_W => BF_SUM_W, BF_DROP => BF_DROP)
        port map (clk => clk, rst => rst, en => t(1), write => write,
                  a => nbb, sum => bfbm(i, j));
      bfc : entity work.block_filter
        generic map (IN_W => M_W, BF_SUM_W => BF_SUM_W, BF_DROP => BF_DROP)
        port map (clk => clk, rst => rst, en => t(1), write => write,
                  a => nbc, sum => bfcm(i, j));
      hr : entity work.harris_response
        generic map (BF_W => BF_W, RESP_W => RESP_W, KTR_W => KTR_W,
                     K_SHIFT1 => K_SHIFT1, K_SHIFT2 => K_SHIFT2)
        port map (clk => clk, rst => rst, en0 => t(2), en1 => t(3), write => write,
                  a => bfam(i, j), b => bfbm(i, j), c => bfcm(i, j), r => hrm(i, j));
      th : entity work.threshold
        generic map (RESP_W => RESP_W)
        port map (clk => clk, rst => rst, en => t(5), write => write,
                  r0 => hrm(i, j), thr => thr, r1 => trm(i, j));
    end generate cols3;
  end generate rows3;

  fm : entity work.find_max
    generic map (IMG_WIDTH => IMG_WIDTH, IMG_HEIGHT => IMG_HEIGHT, RESP_W => RESP_W)
    port map (clk => clk, rst => rst, en => t(4), write => write,
              response => hrm(2, 2), max => max);

  -- thr = floor(max / 2^THR_SHIFT1) + floor(max / 2^THR_SHIFT2), in RESP_W bits
  thr <= resize(max(RESP_W - 1 downto THR_SHIFT1), RESP_W)
       + resize(max(RESP_W - 1 downto THR_SHIFT2), RESP_W);

  lm : entity work.local_maximum
    generic map (RESP_W => RESP_W)
    port map (r => trm, corner => cornerbit);

  sr : entity work.corner_shift_register
    port map (clk => clk, rst => rst, write => write, corner => cornerbit,
              corner_sr => corner_sr);

  corner_o <= (31 downto 4 => '0') & corner_sr;
  corner   <= corner_o;

  observed : if OBSERVE generate
    pack : process (all) is
      variable v : std_ulogic_vector(obs'range);
      variable p : natural;
      procedure put(x : std_ulogic_vector) is
      begin
        v(p to p + x'length - 1) := x;
        p := p + x'length;
      end procedure;
      procedure put(x : std_ulogic) is
      begin
        v(p) := x;
        p := p + 1;
      end procedure;
    begin
      p := 0;
      put(load);
      put(ready);
      put(std_ulogic_vector(t));
      for i in 1 to 7 loop
        for j in 1 to 7 loop
          put(std_ulogic_vector(icm(i, j)));
        end loop;
      end loop;
      for i in 1 to 5 loop for j in 1 to 5 loop put(std_ulogic_vector(sxm(i, j))); end loop; end loop;
      for i in 1 to 5 loop for j in 1 to 5 loop put(std_ulogic_vector(sym(i, j))); end loop; end loop;
      for i in 1 to 5 loop for j in 1 to 5 loop put(std_ulogic_vector(mam(i, j))); end loop; end loop;
      for i in 1 to 5 loop for j in 1 to 5 loop put(std_ulogic_vector(mbm(i, j))); end loop; end loop;
      for i in 1 to 5 loop for j in 1 to 5 loop put(std_ulogic_vector(mcm(i, j))); end loop; end loop;
      for i in 1 to 3 loop for j in 1 to 3 loop put(std_ulogic_vector(bfam(i, j))); end loop; end loop;
      for i in 1 to 3 loop for j in 1 to 3 loop put(std_ulogic_vector(bfbm(i, j))); end loop; end loop;
      for i in 1 to 3 loop for j in 1 to 3 loop put(std_ulogic_vector(bfcm(i, j))); end loop; end loop;
      for i in 1 to 3 loop for j in 1 to 3 loop put(std_ulogic_vector(hrm(i, j))); end loop; end loop;
      put(std_ulogic_vector(max));
      put(std_ulogic_vector(thr));
      for i in 1 to 3 loop for j in 1 to 3 loop put(std_ulogic_vector(trm(i, j))); end loop; end loop;
      put(cornerbit);
      put(std_ulogic_vector(corner_sr));
      put(std_ulogic_vector(corner_o));
      obs <= v;
    end process pack;
  end generate observed;

  not_observed : if not OBSERVE generate
    obs <= (others => '0');
  end generate not_observed;
end architecture rtl;
