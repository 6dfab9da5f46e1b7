#!/usr/bin/env bash
# Installs every Debian 12 package phongsim needs. Idempotent: installs only what is missing,
# and runs `apt-get update` only when something must be installed.
set -euo pipefail

packages=(
  build-essential cmake ninja-build   # C++20 toolchain and build
  verilator zlib1g-dev                # RTL simulation (zlib for FST waveforms)
  iverilog                            # the second simulator (--simulator icarus)
  lcov                                # genhtml: the HTML report of cosim --coverage
  libfmt-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libgtest-dev
  libpng-dev                          # PNG images (sim/render/image.h)
  libssl-dev                          # SHA-256 of what a verdict rests on (base/file_util.h)
  libtinyobjloader-dev                # OBJ meshes (sim/render/mesh.h)
  python3                             # tests/gen_fx_cosim.py writes a test top at configure time
  python3-matplotlib                  # every figure: grids, scanline and Pareto plots (scripts/plot.py)
  pybind11-dev python3-dev python3-numpy  # the Python module (python/) and its example
  yosys                               # synthesis checks (no latches) of every RTL top
  z3                                  # bounded proofs of the stream primitives (yosys-smtbmc)
  nextpnr-ice40                       # iCE40 place and route: fmax of a configuration (sim/explore/synth.h)
  clang-format                        # style check in the test suite
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo=sudo; fi
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
