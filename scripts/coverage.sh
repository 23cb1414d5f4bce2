#!/usr/bin/env bash
# Line coverage of src/ reached by sets of tests: clang 14's source-based coverage, in a clang build
# like the sanitizer step's (-O1, the SIMD cpu backend, no CUDA) but without the sanitizers, which
# add checks to the lines that run, not lines (build-coverage/, or $COVERAGE_BUILD_DIR).
#
#   scripts/coverage.sh [LABEL_REGEX ...]
#
# Each argument is one ctest -L selection (default '^(unit|hostile)$', what the sanitizer step
# runs); for each, the lines of src/ it executes, as the tests and every tool they start run them.
# A selection '!REGEX' is ctest -LE REGEX: '!^(install|slurm|python)$' is the whole suite but for
# what cannot run sanitized. Reports go to build-coverage/coverage/<n>.txt.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${COVERAGE_BUILD_DIR:-$root/build-coverage}"
selections=("$@")
[ ${#selections[@]} -eq 0 ] && selections=('^(unit|hostile)$')
source "$root/scripts/ccache_env.sh"

mkdir -p "$build"
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1" -DLIDAR_SGM_COVERAGE=ON -DLIDAR_SGM_BUILD_TESTS=ON \
  -DLIDAR_SGM_WITH_CUDA=OFF -DLIDAR_SGM_WITH_CPU_BACKEND=ON -DLIDAR_SGM_BUILD_PYTHON=OFF \
  "${lidar_sgm_launcher[@]}" > "$build/coverage-configure.log" || { cat "$build/coverage-configure.log"; exit 1; }
cmake --build "$build" -j"$(nproc)" > "$build/coverage-build.log" 2>&1 || { tail -40 "$build/coverage-build.log"; exit 1; }

# Every executable of the build: the test suites and the tools the tests start.
binaries=()
while IFS= read -r f; do
  [ "$(head -c 4 "$f" | tr -d '\0' | tail -c 3)" = "ELF" ] && binaries+=("$f")
done < <(find "$build/tests" "$build/apps" "$build/bench" -type f -perm -u+x ! -name '*.so*' 2>/dev/null | sort)
objects=("${binaries[0]}")
for b in "${binaries[@]:1}"; do objects+=(-object "$b"); done

mkdir -p "$build/coverage"
n=0
for selection in "${selections[@]}"; do
  n=$((n + 1))
  profiles="$build/coverage/profiles-$n"
  rm -rf "$profiles"
  mkdir -p "$profiles"
  if [ "${selection:0:1}" = "!" ]; then filter=(-LE "${selection:1}"); else filter=(-L "$selection"); fi
  # %4m: a pool of 4 files per binary, merged into by every process (the tests and their tools).
  (cd "$build" && LLVM_PROFILE_FILE="$profiles/%4m.profraw" ctest -j"$(nproc)" --timeout 1200 "${filter[@]}" \
     > "$build/coverage/ctest-$n.log" 2>&1) || echo "coverage: some tests of '$selection' failed (build-coverage/coverage/ctest-$n.log)"
  llvm-profdata-14 merge -sparse "$profiles"/*.profraw -o "$build/coverage/$n.profdata"
  llvm-cov-14 report -instr-profile "$build/coverage/$n.profdata" "${objects[@]}" > "$build/coverage/$n.txt" 2>/dev/null || true
  # The files of src/ only. With ccache's base directory the compilers saw relative paths, so the
  # report names them ../src/...; without ccache, $root/src/.... Columns 8 and 9: lines, missed.
  awk -v root="$root/src/" -v selection="$selection" '
    index($1, "../src/") == 1 || index($1, root) == 1 { lines += $8; missed += $9 }
    END { printf "coverage: %s: lines of src/ executed: %.2f %% (%d of %d)\n", selection,
                 100 * (lines - missed) / lines, lines - missed, lines }' "$build/coverage/$n.txt"
done
