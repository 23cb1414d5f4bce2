#!/usr/bin/env bash
# `pip install .` as a user runs it, offline: a virtual environment in a temporary folder (with the
# system's site packages, for Debian's numpy, setuptools and wheel), `pip install
# --no-build-isolation --no-index SOURCE` (setup.py builds the module with CMake, in a temporary
# folder SOURCE/build-pip-test.*: beside build/, so that ccache sees the same relative paths), then, from a neutral folder with no PYTHONPATH, the environment's python imports
# lidar_sgm from the environment and densifies a small frame. Removes everything afterwards.
#
# Usage: pip_install_test.sh PYTHON SOURCE_DIR SAMPLE_DIR [CMAKE_ARGS]
# CMAKE_ARGS (one string of words) go to the module's CMake build: ctest passes the build's own
# CUDA architectures and warning flags, so that ccache (scripts/ccache_env.sh) hits what the build compiled.
set -euo pipefail
if [ $# -lt 3 ] || [ $# -gt 4 ]; then
  echo "usage: $0 PYTHON SOURCE_DIR SAMPLE_DIR [CMAKE_ARGS]" >&2
  exit 2
fi
python="$1"
source_dir="$2"
sample_dir="$3"
work="$(mktemp -d "${TMPDIR:-/tmp}/lidar_sgm_pip_test.XXXXXX")"
cmake_build="$(mktemp -d "$source_dir/build-pip-test.XXXXXX")"
trap 'rm -rf "$work" "$cmake_build"' EXIT
unset PYTHONPATH PYTHONHOME
export PYTHONNOUSERSITE=1 PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_NO_INPUT=1

start=$SECONDS
"$python" -m venv --system-site-packages "$work/venv"
echo "== venv: $((SECONDS - start)) s"

start=$SECONDS
LIDAR_SGM_PIP_BUILD_DIR="$cmake_build" LIDAR_SGM_CMAKE_ARGS="${4:-}" \
  "$work/venv/bin/python" -m pip install --no-build-isolation --no-index "$source_dir" > "$work/pip.log" 2>&1 ||
  { cat "$work/pip.log"; echo "FAILED: pip install" >&2; exit 1; }
tail -n 2 "$work/pip.log"
echo "== pip install: $((SECONDS - start)) s"

mkdir "$work/neutral"
cd "$work/neutral"
"$work/venv/bin/python" - "$work/venv" "$sample_dir" <<'EOF'
import sys
import numpy as np
import lidar_sgm
venv, sample = sys.argv[1], sys.argv[2]
assert lidar_sgm._lidar_sgm.__file__.startswith(venv + "/"), lidar_sgm._lidar_sgm.__file__
calibration = lidar_sgm.read_calibration(f"{sample}/calib/000000.txt")
points = lidar_sgm.read_kitti_bin(f"{sample}/velodyne/000000.bin")
left, right = (lidar_sgm.read_image(f"{sample}/image_{i}/000000.png") for i in (2, 3))
# A small frame: 320 x 128 pixels of the sample (bottom, centred on the principal point), K moved with them.
width, height = 320, 128
x0, y0 = int(calibration.K[0, 2]) - width // 2, left.shape[0] - height
K = calibration.K.copy()
K[0, 2] -= x0
K[1, 2] -= y0
small = lidar_sgm.Calibration(K, calibration.baseline, calibration.T_cam_lidar, width, height)
crop = (slice(y0, y0 + height), slice(x0, x0 + width))
result = lidar_sgm.Densifier(small, num_disparities=64).densify(points, left[crop], right[crop])
assert result.mode == "fused" and len(result.points) > 0 and result.point_confidence is not None, result
assert np.isfinite(result.points).all()
print(f"lidar_sgm {lidar_sgm.__version__} from {lidar_sgm.__file__}: {len(result.points)} points")
EOF
echo "pip install test: passed"
