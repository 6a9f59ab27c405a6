#!/bin/sh
# libfuzzer.sh BUILD_DIR OUT: builds the fuzz targets under libFuzzer (clang++
# -fsanitize=fuzzer,address,undefined) against the project's libraries as BUILD_DIR built
# them (the link line of hc-fuzz, whose driver it replaces), as OUT/hc-libfuzzer.
#   HC_FUZZ_TARGET=formats-json OUT/hc-libfuzzer -max_total_time=60 -seed=1 corpus/
# Only the targets and libFuzzer are instrumented for coverage; the libraries are the
# build's own (g++).
set -e
build=$(cd "$1" && pwd); out=$(mkdir -p "$2" && cd "$2" && pwd)
src=$(cd "$(dirname "$0")/../.." && pwd)
cd "$build/tests/fuzz"
flags="-O1 -g -fsanitize=fuzzer,address,undefined -std=c++20 -DFMT_SHARED -DHC_SOURCE_DIR=\"$src\" -I$src
       -isystem /usr/include/opencv4 -isystem /usr/include/eigen3"
clang++ $flags -c "$src/tests/fuzz/fuzz_targets.cpp" -o "$out/fuzz_targets.o"
clang++ $flags -c "$src/tests/fuzz/libfuzzer_entry.cpp" -o "$out/libfuzzer_entry.o"
# the libraries of hc-fuzz's link line: everything after "-o hc-fuzz"
libs=$(sed -e 's|^.*-o hc-fuzz||' CMakeFiles/hc-fuzz.dir/link.txt)
eval clang++ -fsanitize=fuzzer,address,undefined "$out/libfuzzer_entry.o" "$out/fuzz_targets.o" -o "$out/hc-libfuzzer" $libs
echo "built $out/hc-libfuzzer"
