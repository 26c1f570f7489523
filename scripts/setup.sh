#!/usr/bin/env bash
# cosim setup: installs every Debian package the project uses and prepares the OpenFOAM v1912
# headers (from Debian's source package) into a cache folder. Idempotent: a second run only
# checks and returns in seconds.
#
#   scripts/setup.sh            install packages + OpenFOAM headers
#   COSIM_CACHE=/path ...       where the OpenFOAM headers go (default: <repo>/.cache)
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cache="${COSIM_CACHE:-$repo/.cache}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

packages=(
  build-essential cmake ninja-build pkg-config git
  openfoam libopenfoam
  liggghts libliggghts-dev libopenmpi-dev openmpi-bin
  cppzmq-dev libzmq3-dev
  libprotobuf-dev protobuf-compiler
  libhdf5-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev
  python3 python3-numpy python3-scipy python3-matplotlib python3-h5py
  paraview python3-paraview xvfb xauth   # tests/paraview: particles.xmf as ParaView shows it
  dpkg-dev
  clang libclang-rt-14-dev    # libFuzzer targets (scripts/fuzz.sh)
  clang-format                # scripts/format-check.sh, run by scripts/test.sh
  clang-tidy                  # scripts/tidy.sh, run by scripts/test.sh
  slurmd slurmctld slurm-client munge   # launch: slurm, tested on a one-node cluster (scripts/local-slurm.sh)
  iproute2 util-linux mount   # tests/scenarios/own_folder_test.cpp: ip netns, unshare, mount
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[setup] installing: ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "[setup] Debian packages: all present"
fi

# ---- OpenFOAM v1912 headers from Debian's source package --------------------------------------
of_root="$cache/openfoam-src"
stamp="$cache/openfoam-headers.stamp"
if [ -f "$stamp" ]; then
  echo "[setup] OpenFOAM headers: ready in $of_root"
else
  if ! apt-get indextargets 2>/dev/null | grep -q 'Created-By: Sources'; then
    echo "[setup] adding a deb-src entry for Debian's source packages"
    src_list=/etc/apt/sources.list.d/cosim-deb-src.sources
    $SUDO tee "$src_list" >/dev/null <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
    $SUDO apt-get update -qq
  fi
  version="$(dpkg-query -W -f='${Version}' openfoam)"
  mkdir -p "$cache/dl"
  (cd "$cache/dl" && apt-get source -qq --download-only "openfoam=$version")
  rm -rf "$of_root" "$cache/extract"
  mkdir -p "$cache/extract"
  dsc="$(ls "$cache"/dl/openfoam_*.dsc | head -1)"
  (cd "$cache/extract" && dpkg-source --no-check -x "$dsc" src >/dev/null)
  mv "$cache/extract/src" "$of_root"
  rm -rf "$cache/extract"
  echo "[setup] building lnInclude trees"
  # The folders our adapter compiles against.
  for d in OpenFOAM OSspecific/POSIX finiteVolume meshTools fileFormats surfMesh \
           thermophysicalModels/basic thermophysicalModels/specie \
           TurbulenceModels/turbulenceModels TurbulenceModels/compressible \
           transportModels/compressible dynamicMesh sampling lagrangian/basic; do
    if [ -d "$of_root/src/$d" ]; then
      (cd "$of_root/src/$d" && WM_PROJECT_DIR="$of_root" "$of_root/wmake/wmakeLnInclude" -u . >/dev/null)
    fi
  done
  touch "$stamp"
  echo "[setup] OpenFOAM headers ready in $of_root"
fi
echo "[setup] done"
