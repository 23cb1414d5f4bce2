# Shared settings for every lidar_sgm target: warnings (errors in CI), C++17. CUDA sources get
# the host compiler's warnings through nvcc, and nvcc's own warnings as errors in CI.
function(lidar_sgm_target_defaults target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>
      $<$<COMPILE_LANGUAGE:CUDA>:-Xcompiler=-Wall,-Wextra>)
    if(LIDAR_SGM_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE $<$<COMPILE_LANGUAGE:CXX>:-Werror>
                                               $<$<COMPILE_LANGUAGE:CUDA>:-Werror=all-warnings -Xcompiler=-Werror>)
    endif()
  endif()
  target_compile_features(${target} PUBLIC cxx_std_17)
  # A program records only the shared libraries it calls (Debian's linker records every one it is
  # given): each one recorded is loaded, relocated and initialised before main(), whether used or
  # not (BENCHMARK.md, "Start-up").
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "EXECUTABLE" AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang" AND NOT APPLE)
    target_link_options(${target} PRIVATE LINKER:--as-needed)
  endif()
endfunction()
