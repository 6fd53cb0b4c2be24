#!/usr/bin/env bash
# Installs the Debian packages locbench needs, only those that are missing.
# Run as root on Debian 12 (or with sudo available). No network fetches at build time.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  ninja-build          # build tool: keeps both cores busy across targets (make build 140 → 128 s, docs/decisions.md)
  lld                  # linker: the test executables link 4× faster than with GNU ld (CMakeLists.txt)
  libeigen3-dev        # linear algebra (poses, covariances)
  libgtest-dev libgmock-dev   # unit tests
  libbenchmark-dev     # speed kernels
  libfmt-dev           # formatting
  nlohmann-json3-dev   # reports, options, JSON inputs
  libcli11-dev         # command line
  zlib1g-dev           # reading .gz logs in place
  libvalijson-dev      # JSON Schema validation of reports in tests
  librapidcheck-dev    # property tests of the readers
  libboost-dev         # Boost.Math distributions (t, normal, chi-square quantiles), header-only
  libtbb-dev           # oneTBB: Monte-Carlo runs on all cores (task arena + parallel_for)
  libceres-dev         # Ceres Solver 2.1: the ML calibration's least squares and the diagnosis's likelihood fits
  gnuplot-nox          # `locbench report`: charts as SVG, inlined into the HTML page
  chromium             # tests: render the HTML report headless, check charts and console
  parallel             # docs/gnu_parallel.sh: shards on one or several machines (tested)
  clang libclang-rt-14-dev   # fuzz/: libFuzzer targets of the readers (-DLOCBENCH_FUZZ=ON)
  clang-format         # tests: Style.EverySourceIsClangFormatted (.clang-format); `make format`
  universal-ctags      # tests: Style.NoFunctionIsOver120Lines finds each function's extent
  librosbag-storage-dev      # ROS 1 bags: rosbag_storage writes them (tests, simulate --ros1-bag)
  libbz2-dev libroslz4-dev   # ROS 1 bags: compressed chunks (datasets/io/ros1_bag_records.cpp)
  libnav-msgs-dev libsensor-msgs-dev libgeometry-msgs-dev libtf2-msgs-dev   # ROS 1 messages (roscpp serialization)
  libfastcdr-dev libsqlite3-dev   # ROS 2 bags (datasets/io/ros2_bag.cpp): CDR messages in sqlite3 storage
  libzstd-dev liblz4-dev     # ROS 2 bags in MCAP storage (datasets/io/mcap_bag.cpp): compressed chunks
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing missing Debian packages: ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "setup: need root to install ${missing[*]}" >&2; exit 2; fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
