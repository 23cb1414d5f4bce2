#!/usr/bin/env bash
# Installs every Debian package the build, the tools and the tests need. Idempotent: packages
# already present are not fetched again. Runs apt-get as root, or through sudo.
set -euo pipefail

packages=(
  build-essential cmake        # compiler and build system
  libopencv-dev                # io and tools: imgcodecs, imgproc
  libgtest-dev libgmock-dev    # tests
  libeigen3-dev                # geometry
  libhwy-dev                   # the fast cpu backend: SIMD with runtime dispatch (Highway)
  libpcl-dev                   # the PCL class, cloud files, lidar_sgm_densify
  nlohmann-json3-dev           # lidar_sgm_eval's JSON results
  libcli11-dev                 # the tools' and the bench's command lines (CLI11, header-only)
  libopen3d-dev                # lidar_sgm::open3d, densify() on Open3D clouds (0.16; optional: skipped without it)
  pkg-config                   # the install test checks lidar_sgm.pc
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install_deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
echo "install_deps: done"
