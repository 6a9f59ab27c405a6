#!/bin/sh
# Runs the command after `--` only when the KITTI data it needs exists; otherwise prints why
# and exits 77, which CTest reports as a skip (SKIP_RETURN_CODE).
data="${HARRIS_COSIM_DATA:-$1}"
shift
[ "$1" = "--" ] && shift
if [ ! -d "$data/kitti/sequences/01/image_0" ]; then
  echo "SKIP: KITTI sequence 01 not found under '$data' (set HARRIS_COSIM_DATA or put it in ../shared/data)"
  exit 77
fi
exec "$@"
