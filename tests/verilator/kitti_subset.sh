#!/bin/sh
# kitti_subset.sh HARRIS_COSIM DATA_DIR PAIRS JSON: the rtl-full CTest. Streams KITTI
# sequence 01's stereo pairs PAIRS (L R L R ...) through the Verilator netlist against the
# cycle model. DATA_DIR is the default; $HARRIS_COSIM_DATA at test time overrides it, as
# for every other data test. Exits 77 (CTest SKIP_RETURN_CODE) when the data set is not on
# this machine.
exe=$1 data=${HARRIS_COSIM_DATA:-$2} pairs=$3 json=$4
if [ ! -d "$data/kitti/sequences/01/image_0" ]; then
    echo "SKIP: KITTI sequence 01 not found under '$data' (set HARRIS_COSIM_DATA); rtl-full needs it"
    exit 77
fi
exec "$exe" verilate --data "$data" --sequence 01 --pairs "$pairs" --json "$json"
