#!/usr/bin/env bash
# The package as a user gets it: installs a build into a temporary prefix (cmake --install), then
# configures, builds and runs the downstream projects beside this script against that prefix
# (find_package(lidar_sgm CONFIG REQUIRED COMPONENTS ...)), compiles the core user once more with
# pkg-config, runs an installed tool, imports the installed Python package and densifies the sample
# with it, and removes the prefix. Any step failing fails the test.
#
# Usage: run_install_test.sh CMAKE BUILD_DIR CONFIG CXX_COMPILER HAVE_PCL(ON|OFF) SAMPLE_DIR HAVE_OPEN3D(ON|OFF) [PYTHON]
# (PYTHON: the interpreter the package was built for; empty or absent when it was not built)
# (tests/CMakeLists.txt registers it with ctest, label `install`).
set -euo pipefail
if [ $# -ne 7 ] && [ $# -ne 8 ]; then
  echo "usage: $0 CMAKE BUILD_DIR CONFIG CXX_COMPILER HAVE_PCL SAMPLE_DIR HAVE_OPEN3D [PYTHON]" >&2
  exit 2
fi
cmake_command="$1"
build_dir="$2"
config="${3:-Release}"
cxx="$4"
have_pcl="$5"
sample_dir="$6"
have_open3d="${7:-OFF}"
python="${8:-}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

work="$(mktemp -d "${TMPDIR:-/tmp}/lidar_sgm_install_test.XXXXXX")"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

step() { echo; echo "== $*"; }

step "cmake --install $build_dir --prefix $prefix"
"$cmake_command" --install "$build_dir" --prefix "$prefix" --config "$config" > "$work/install.log" ||
  { cat "$work/install.log"; exit 1; }
(cd "$prefix" && find . -type f | sort | sed 's/^/  /')

# What a user must never get: private headers (src/, the backends' stage contract) or the
# backends' object libraries as separate things.
if find "$prefix" -path '*backends*' | grep -q .; then
  echo "FAILED: the backends are private, but the prefix has:" >&2
  find "$prefix" -path '*backends*' >&2
  exit 1
fi
for file in include/lidar_sgm/version.hpp include/lidar_sgm/core/matcher.hpp; do
  [ -f "$prefix/$file" ] || { echo "FAILED: $file is not installed" >&2; exit 1; }
done

# Configures and builds downstream project $1 against the prefix only, with extra CMake arguments.
build_downstream() {
  local name="$1"
  shift
  "$cmake_command" -S "$here/$name" -B "$work/build-$name" -DCMAKE_BUILD_TYPE="$config" \
    -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$prefix" "$@"
  # The package must be the one just installed, not one elsewhere on the machine.
  local found
  found="$(grep '^lidar_sgm_DIR:' "$work/build-$name/CMakeCache.txt" | cut -d= -f2-)"
  case "$found" in
    "$prefix"/*) ;;
    *) echo "FAILED: $name found lidar_sgm in '$found', not under $prefix" >&2; exit 1 ;;
  esac
  "$cmake_command" --build "$work/build-$name" -j2
}

step "core user: find_package(lidar_sgm COMPONENTS core) with Eigen, OpenCV, PCL and the CUDA toolkit hidden"
# The core component must not look for any of them (the GPU machine has none of the first three; a
# CPU-only user need not have CUDA, even when the core was built with the cuda backend): no nvcc on
# PATH, no toolkit where CUDAToolkit_ROOT points, and find_package(CUDAToolkit) disabled.
no_cuda_path="$(printf '%s' "$PATH" | tr ':' '\n' | grep -v -i cuda | paste -sd: -)"
PATH="$no_cuda_path" CUDACXX='' CUDA_PATH='' build_downstream core_user -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_OpenCV=ON -DCMAKE_DISABLE_FIND_PACKAGE_PCL=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_CUDAToolkit=ON -DCUDAToolkit_ROOT="$work/no-cuda-here"
"$work/build-core_user/core_user"

step "core user again, compiled with a plain pkg-config --cflags --libs (lidar_sgm.pc)"
pc_file="$(find "$prefix" -name lidar_sgm.pc | head -n 1)"
[ -n "$pc_file" ] || { echo "FAILED: lidar_sgm.pc is not installed" >&2; exit 1; }
export PKG_CONFIG_PATH="$(dirname "$pc_file")"
version="$(pkg-config --modversion lidar_sgm)"
# A shared core in a prefix the loader does not search: found through the libdir pkg-config names.
libdir="$(pkg-config --variable=libdir lidar_sgm)"
# What the installed libraries need, static or shared, is in Libs/Requires: no --static needed.
# shellcheck disable=SC2046  # pkg-config's output is a list of flags
"$cxx" -std=c++17 -O1 -DEXPECTED_VERSION="\"$version\"" $(pkg-config --cflags lidar_sgm) \
  "$here/core_user/main.cpp" -o "$work/core_user_pkgconfig" $(pkg-config --libs lidar_sgm) -Wl,-rpath,"$libdir"
"$work/core_user_pkgconfig"
# --static must link too (it adds the .private fields, if any).
# shellcheck disable=SC2046
"$cxx" -std=c++17 -O1 -DEXPECTED_VERSION="\"$version\"" $(pkg-config --cflags lidar_sgm) \
  "$here/core_user/main.cpp" -o "$work/core_user_pkgconfig_static" $(pkg-config --static --libs lidar_sgm) \
  -Wl,-rpath,"$libdir"
"$work/core_user_pkgconfig_static"

step "a component that does not exist is reported not found"
mkdir -p "$work/bogus"
cat > "$work/bogus/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(bogus LANGUAGES CXX)
find_package(lidar_sgm CONFIG COMPONENTS core bogus)
if(lidar_sgm_FOUND OR lidar_sgm_bogus_FOUND OR NOT lidar_sgm_core_FOUND)
  message(FATAL_ERROR "lidar_sgm_FOUND=${lidar_sgm_FOUND} bogus=${lidar_sgm_bogus_FOUND} core=${lidar_sgm_core_FOUND}")
endif()
EOF
"$cmake_command" -S "$work/bogus" -B "$work/build-bogus" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_PREFIX_PATH="$prefix" > "$work/bogus.log" || { cat "$work/bogus.log"; exit 1; }

# A core-only build (no OpenCV) has no lidar_sgm_disparity; a build with PCL has every tool.
if [ -e "$prefix/bin/lidar_sgm_disparity" ] || [ "$have_pcl" = "ON" ]; then
  step "installed tools run from the prefix (their libraries found through their RPATH)"
  for tool in lidar_sgm_disparity lidar_sgm_synth lidar_sgm_densify lidar_sgm_eval; do
    [ "$have_pcl" = "ON" ] || [ "$tool" = lidar_sgm_disparity ] || [ "$tool" = lidar_sgm_synth ] || continue
    "$prefix/bin/$tool" -h > /dev/null || { echo "FAILED: $tool -h" >&2; exit 1; }
  done
fi

if [ "$have_pcl" = "ON" ]; then
  step "PCL user: find_package(lidar_sgm COMPONENTS core pipeline io pcl), SGMDensification on $sample_dir"
  build_downstream pcl_user
  "$work/build-pcl_user/pcl_user" "$sample_dir"
  step "sequence user: find_package(lidar_sgm COMPONENTS sequence), the frames of $sample_dir"
  build_downstream sequence_user
  "$work/build-sequence_user/sequence_user" "$sample_dir" | tail -n 1 | grep -q "KITTI object layout" ||
    { echo "FAILED: sequence_user did not read $sample_dir as a KITTI object layout" >&2; exit 1; }
else
  step "PCL user skipped: this build has no PCL"
fi

if [ -n "$python" ]; then
  step "Python: import lidar_sgm from the prefix, densify $sample_dir"
  init="$(find "$prefix" -path '*/lidar_sgm/__init__.py' | head -n 1)"
  [ -n "$init" ] || { echo "FAILED: the Python package lidar_sgm is not installed" >&2; exit 1; }
  for file in __init__.pyi py.typed; do
    [ -f "$(dirname "$init")/$file" ] || { echo "FAILED: lidar_sgm/$file is not installed" >&2; exit 1; }
  done
  # Run from the temporary folder, so that nothing but PYTHONPATH can lead to a lidar_sgm.
  (cd "$work" && PYTHONPATH="$(dirname "$(dirname "$init")")" PYTHONDONTWRITEBYTECODE=1 "$python" - "$prefix" "$sample_dir" <<'EOF'
import sys
import lidar_sgm
prefix, sample = sys.argv[1], sys.argv[2]
assert lidar_sgm.__file__.startswith(prefix), lidar_sgm.__file__
assert lidar_sgm._lidar_sgm.__file__.startswith(prefix), lidar_sgm._lidar_sgm.__file__
calibration = lidar_sgm.read_calibration(f"{sample}/calib/000000.txt")
points = lidar_sgm.read_kitti_bin(f"{sample}/velodyne/000000.bin")
left, right = (lidar_sgm.read_image(f"{sample}/image_{i}/000000.png") for i in (2, 3))
result = lidar_sgm.Densifier(calibration).densify(points, left, right)
assert result.mode == "fused" and len(result.points) > 100000, (result.mode, len(result.points))
print(f"lidar_sgm {lidar_sgm.__version__} from {lidar_sgm.__file__}: {len(result.points)} points")
EOF
  )
else
  step "Python skipped: this build has no Python package"
fi

if [ "$have_open3d" = "ON" ]; then
  step "Open3D component alone: found with OpenCV and PCL hidden"
  # lidar_sgm::open3d stands on the pipeline only: it must not look for either.
  mkdir -p "$work/open3d_only"
  cat > "$work/open3d_only/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(open3d_only LANGUAGES CXX)
find_package(lidar_sgm CONFIG REQUIRED COMPONENTS open3d)
if(NOT TARGET lidar_sgm::open3d OR TARGET lidar_sgm::io OR TARGET lidar_sgm::pcl)
  message(FATAL_ERROR "COMPONENTS open3d loaded the wrong targets")
endif()
EOF
  "$cmake_command" --no-warn-unused-cli -S "$work/open3d_only" -B "$work/build-open3d_only" -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_DISABLE_FIND_PACKAGE_OpenCV=ON -DCMAKE_DISABLE_FIND_PACKAGE_PCL=ON \
    > "$work/open3d_only.log" || { cat "$work/open3d_only.log"; exit 1; }

  step "Open3D user: find_package(lidar_sgm COMPONENTS open3d io), densify() on $sample_dir read by Open3D"
  build_downstream open3d_user
  "$work/build-open3d_user/open3d_user" "$sample_dir"
else
  step "Open3D user skipped: this build has no Open3D"
fi

echo
echo "install test: passed"
