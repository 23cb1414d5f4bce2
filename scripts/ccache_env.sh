# Sourced by scripts/build.sh, scripts/test.sh and scripts/test_sanitizers.sh (which set $root to
# the checkout): when ccache is installed, every compiler (C++ and CUDA) goes through it, set up so
# that a fresh clone in another folder hits the cache an earlier build on this machine filled.
#  - CCACHE_BASEDIR=the checkout: absolute paths under it (sources, -I, the build folder) are
#    hashed as paths relative to the compiler's working folder, the same in every clone;
#  - CCACHE_NOHASHDIR: the working folder itself is not hashed (ccache hashes it when -g is on, as
#    in the sanitizer build, so that debug info names the right folder; we trade that for hits);
#  - CCACHE_COMPILERCHECK=content: a compiler is known by its bytes, not its file's time, so that
#    a compiler reinstalled by apt-get with the same bytes still hits.
# Variables the user already set win. Without ccache, or with LIDAR_SGM_CCACHE=0, nothing changes:
# lidar_sgm_launcher is empty.
lidar_sgm_launcher=()
if [ "${LIDAR_SGM_CCACHE:-1}" != "0" ] && command -v ccache > /dev/null; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}"
  export CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
  export CCACHE_COMPILERCHECK="${CCACHE_COMPILERCHECK:-content}"
  lidar_sgm_launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_CUDA_COMPILER_LAUNCHER=ccache)
fi
