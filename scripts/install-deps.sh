#!/usr/bin/env bash
# Installs what pss needs from Debian 12's archive (root or sudo). Quiet when all is there.
# --optional adds what the optional targets need (scripts/test.sh): PCL for the peer benchmark
# bench/peer_pcl_mls, so that a default build on a machine with PCL is built in CI too, and
# Open MPI for `mpirun -np N pss project` (its tests run 2 and 3 ranks on this machine).
set -euo pipefail
packages=(g++ cmake ninja-build pkg-config libglm-dev libcli11-dev libstb-dev nlohmann-json3-dev
          libnanoflann-dev zlib1g-dev libnifti2-dev libopenexr-dev libgtest-dev libgmock-dev
          libglfw3-dev libimgui-dev xvfb xauth libgl1-mesa-dri
          python3-dev pybind11-dev python3-numpy python3-pytest)
[[ ${1:-} == --optional ]] && packages+=(libpcl-dev libopenmpi-dev openmpi-bin)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [[ $(id -u) -eq 0 ]] || sudo="sudo"
  echo "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi
