#!/usr/bin/env bash
# Installs every Debian package the build, the tools and the tests need. Idempotent: packages
# already present are not fetched again. Runs apt-get as root, or through sudo.
set -euo pipefail

packages=(
  build-essential cmake        # compiler and build system
  ccache                       # compiler cache: scripts/build.sh, test.sh and test_sanitizers.sh use it
  libopencv-dev                # io and tools: core, imgproc (images in memory); tests and eval: imgcodecs
  libpng-dev libjpeg-dev       # io: PNG in and out, JPEG in (without OpenCV's imgcodecs and its ~130 libraries)
  libyaml-cpp-dev              # io: the calibration YAML reader (OpenCV's parser hung on hostile files)
  libgtest-dev libgmock-dev    # tests
  libeigen3-dev                # geometry
  libhwy-dev                   # the fast cpu backend: SIMD with runtime dispatch (Highway)
  libpcl-dev                   # the PCL class, cloud files, lidar_sgm_densify
  liblzf-dev                   # io: binary_compressed PCD out (without PCL io and its VTK/OpenNI chain)
  libjemalloc-dev              # the one-shot tools' allocator, on huge pages (apps/common/one_shot_allocator.cpp)
  nlohmann-json3-dev           # lidar_sgm_eval's JSON results
  libcli11-dev                 # the tools' and the bench's command lines (CLI11, header-only)
  libopen3d-dev                # lidar_sgm::open3d, densify() on Open3D clouds (0.16; optional: skipped without it)
  pkg-config                   # the install test checks lidar_sgm.pc
  slurm-wlm munge              # the Slurm job array test: its own slurmctld, slurmd and munged
  python3-dev pybind11-dev     # the Python package lidar_sgm (python/)
  python3-numpy python3-pytest # its arrays and its tests
  python3-venv python3-pip     # pip install . of the package into a virtual environment (tested, offline)
  python3-setuptools python3-wheel  # ... its build backend (setup.py), without fetching one
  python3-open3d               # lidar_sgm.to_open3d, tested
  python3-matplotlib           # examples/densify_kitti.py's color map
  clang-14 libclang-rt-14-dev  # scripts/test_sanitizers.sh: ASan, UBSan and libFuzzer (-fsanitize=fuzzer)
  libomp-14-dev                # ... and OpenMP for clang, so the sanitized cpu backend runs its threads
  llvm-14                      # scripts/coverage.sh: llvm-profdata and llvm-cov
  python3                      # ... tests/fuzz/make_seeds.py, the fuzz targets' seeds
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

# Debian's munge, slurmctld and slurmd start their services when installed (invoke-rc.d, or
# deb-systemd-invoke under systemd): nothing here wants them running (the Slurm test starts its own
# on private paths), and where they cannot start (a container without an init system) the failed
# start may fail the install. A policy-rc.d answering 101 ("action forbidden") while apt-get runs keeps every service
# from starting; one already there (Docker images ship one) is left as it is.
policy=/usr/sbin/policy-rc.d
if [ ! -e "$policy" ]; then
  trap '$SUDO rm -f "$policy"' EXIT
  printf '#!/bin/sh\n# scripts/install_deps.sh: no service starts while it installs packages.\nexit 101\n' |
    $SUDO tee "$policy" > /dev/null
  $SUDO chmod 755 "$policy"
fi
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
echo "install_deps: done"
