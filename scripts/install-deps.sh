#!/usr/bin/env bash
# Installs the Debian 12 (bookworm) packages flaplag needs to build, test and benchmark.
# Non-interactive; run as root (re-runs itself with sudo when that is available).
set -euo pipefail

if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    exec sudo -- "$0" "$@"
  fi
  echo "install-deps.sh: must run as root" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
apt-get update
# Ninja runs the build (on two cores it keeps both busy where make idles one).  GiNaC (with CLN)
# runs the symbolic derivation at build time; toml++ reads the ordering specs; Eigen, CLI11 and
# nlohmann-json are the runtime and the command line; GoogleTest and Google Benchmark are the
# tests and bench/.  The Python module (python/) is built with pybind11 for Debian's
# /usr/bin/python3 and uses numpy; its tests use pytest, dask.distributed (maps on a cluster) and
# matplotlib (examples/python/).  gnuplot draws the pictures; headless Chromium opens the HTML
# reports in the tests (tests/report_test.cpp), with DejaVu for their text.  ccache lets the
# second sanitizer build of .ci/run reuse the objects of the first instead of recompiling them.
apt-get install -y --no-install-recommends \
  build-essential \
  ccache \
  cmake \
  ninja-build \
  pkg-config \
  libginac-dev \
  libcln-dev \
  libeigen3-dev \
  libgtest-dev \
  libbenchmark-dev \
  libcli11-dev \
  nlohmann-json3-dev \
  libtomlplusplus-dev \
  python3-dev \
  pybind11-dev \
  python3-pybind11 \
  python3-numpy \
  python3-pytest \
  python3-distributed \
  python3-matplotlib \
  gnuplot-nox \
  chromium \
  fonts-dejavu-core
