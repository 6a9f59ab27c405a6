#!/bin/sh
# The observation port must not change the design: synthesise harris_top with OBSERVE=false,
# and harris_top with OBSERVE=true inside a wrapper that leaves `obs` open, with GHDL; let
# yosys elaborate, flatten and optimise both; their cell statistics must be identical.
#   obs_port_synthesis.sh RTL_DIR WRAPPER_VHD
set -eu
rtl="$1"; wrapper="$2"
command -v yosys >/dev/null || { echo "SKIP: yosys not installed"; exit 77; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
ghdl -a --std=08 "$rtl/harris_pkg.vhd" "$rtl/load_control.vhd" "$rtl/input_converter.vhd" \
  "$rtl/input_converter_mux.vhd" "$rtl/control_shift_register.vhd" "$rtl/sobel_x.vhd" "$rtl/sobel_y.vhd" \
  "$rtl/m_products.vhd" "$rtl/block_filter.vhd" "$rtl/harris_response.vhd" "$rtl/find_max.vhd" \
  "$rtl/threshold.vhd" "$rtl/local_maximum.vhd" "$rtl/corner_shift_register.vhd" "$rtl/harris_top.vhd" "$wrapper"
ghdl --synth --std=08 -gOBSERVE=false -gIMG_WIDTH=40 -gIMG_HEIGHT=30 --out=verilog harris_top > closed.v
ghdl --synth --std=08 --out=verilog harris_top_obs_open > open.v
for v in closed open; do
  top=harris_top; [ $v = open ] && top=harris_top_obs_open
  yosys -q -p "read_verilog $v.v; hierarchy -top $top; proc; flatten; opt -full; opt_clean -purge; tee -q -o $v.stat stat" >/dev/null
  grep -E '^ +(Number of cells|\$)' $v.stat > $v.cells
done
echo "cells without the port: $(grep 'Number of cells' closed.cells)"
echo "cells with the port open: $(grep 'Number of cells' open.cells)"
if diff closed.cells open.cells; then
  echo "PASS: identical cell statistics"
else
  echo "FAIL: the observation port changes the synthesised design"
  exit 1
fi
