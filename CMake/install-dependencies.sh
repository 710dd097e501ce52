#!/bin/sh
# Installs the Debian 12 packages VIMLOP needs to build, test and run its demo.
# Only missing packages are requested; apt runs as root or through sudo.
# Extra package names as arguments are installed too (make fuzz: clang).
set -eu

packages="
cmake
ninja-build
g++
make
ccache
libeigen3-dev
libembree-dev
libvtk9-dev
libx11-dev
python3-vtk9
python3-numpy
python3-h5py
python3-dev
libinsighttoolkit5-dev
libgdcm-dev
libgdcm-tools
libopencv-dev
libopencv-contrib-dev
ffmpeg
libgtest-dev
libgmock-dev
libcli11-dev
nlohmann-json3-dev
libopenigtlink-dev
libopen3d-dev
zlib1g-dev
elastix
xvfb
xauth
chromium
libgl1-mesa-dri
colmap
invesalius-examples
munge
slurmctld
slurmd
slurm-client
iproute2
$*
"

missing=""
for p in $packages; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done

if [ -z "$missing" ]; then
  echo "install-dependencies: all $(echo $packages | wc -w) packages are installed"
  exit 0
fi

echo "install-dependencies: installing:$missing"
if [ "$(id -u)" -eq 0 ]; then
  sudo=""
elif command -v sudo >/dev/null 2>&1; then
  sudo="sudo"
else
  echo "install-dependencies: need root or sudo to run: apt-get install$missing" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
# shellcheck disable=SC2086
$sudo apt-get install -y -q --no-install-recommends $missing
