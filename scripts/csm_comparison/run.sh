#!/bin/sh
# Censi's CSM (PL-ICP, C) against locbench's PL-ICP on the relation pairs of laser/real_logs
# (Intel, ACES), in one process, alternating, each pair's time the minimum of 5 repetitions.
# A one-off measurement, not part of the build or the tests: it needs libgsl-dev, network access
# to clone CSM (pinned below) and the Release benchmark build of `make bench` (build/bench).
#   scripts/csm_comparison/run.sh            (LOCBENCH_DATA: the datasets, as everywhere)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
work=${CSM_WORK:-/tmp/locbench_csm}
commit=dff2557  # AndreaCensi/csm master, 2019
bench=$root/build/bench
command -v gsl-config >/dev/null || apt-get install -y libgsl-dev
[ -d "$work/csm" ] || git clone -q https://github.com/AndreaCensi/csm "$work/csm"
git -C "$work/csm" checkout -q "$commit"
cmake -Wno-dev -S "$work/csm" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O3 -DNDEBUG" >/dev/null
cmake --build "$work/build" --target csm -j"$(nproc)" >/dev/null
[ -x "$bench/benchmarks/speed/locbench_speed" ] || make -C "$root" bench >/dev/null
# locbench's libraries, as locbench_speed links them.
libs=$(tr ' ' '\n' <"$bench/benchmarks/speed/CMakeFiles/locbench_speed.dir/link.txt" |
  grep -E '\.a$|\.so|^-l' | grep -v benchmark.so |
  sed "s#^\.\./\.\./#$bench/#; s#^\.\./experiments/#$bench/benchmarks/experiments/#")
g++ -O3 -DNDEBUG -std=c++20 -DFMT_SHARED -DBOOST_ALL_NO_LIB -I"$root" -isystem /usr/include/eigen3 \
  -I"$work/csm/sm" -I"$work/csm/sm/lib" -I"$work/build" "$here/csm_comparison.cpp" -o "$work/csm_comparison" \
  -fuse-ld=lld -Wl,--start-group $libs -Wl,--end-group "$work/build/sm/libcsm.so" -lgsl -lgslcblas -lfmt -ltbb -lz \
  -Wl,-rpath,"$work/build/sm"
"$work/csm_comparison"
