#!/usr/bin/env bash
# Installs dependencies, builds (Release, warnings as errors) and runs every test.
# Tests that need ../shared/data skip (with a message) when it is absent. Then the sanitizer step
# (scripts/test_sanitizers.sh: ASan + UBSan suite, fuzz targets, regression corpus);
# LIDAR_SGM_SKIP_SANITIZERS=1 skips it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh" -DLIDAR_SGM_WARNINGS_AS_ERRORS=ON -DLIDAR_SGM_BUILD_TESTS=ON
cd "$build_dir"
ctest --output-on-failure -j"$(nproc)" --timeout 1200
"$root/scripts/test_sanitizers.sh"
