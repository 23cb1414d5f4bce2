# Packaging: `cmake --install` lays out the libraries, their public headers, the tools, a CMake
# package (find_package(lidar_sgm CONFIG COMPONENTS ...)) and a pkg-config file for the core.
#
# One export set per component (lidar_sgm_<component>Targets.cmake), so that a user who asks for
# the core loads neither Eigen nor OpenCV nor PCL nor Open3D (the GPU machine has none of them); the Config
# loads a component's targets after those of the components it depends on.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(LIDAR_SGM_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/lidar_sgm"
    CACHE STRING "Where the CMake package files are installed, relative to the prefix")

# The public libraries, in dependency order (each may use only those before it): the Config
# relies on this order when it loads the targets.
set(LIDAR_SGM_PACKAGE_COMPONENTS core geometry pipeline io pcl sequence open3d)

# 0.x: every minor release may change the ABI (the Matcher class, the Densifier, the PCL class
# layout all still move), so the soname carries major.minor; from 1.0 on, the major alone.
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(LIDAR_SGM_SOVERSION "${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}")
else()
  set(LIDAR_SGM_SOVERSION "${PROJECT_VERSION_MAJOR}")
endif()

# Installed tools find the installed shared libraries next door, wherever the prefix is moved to.
if(NOT DEFINED CMAKE_INSTALL_RPATH)
  file(RELATIVE_PATH _lidar_sgm_bin_to_lib "/prefix/${CMAKE_INSTALL_BINDIR}" "/prefix/${CMAKE_INSTALL_LIBDIR}")
  set(CMAKE_INSTALL_RPATH "$ORIGIN/${_lidar_sgm_bin_to_lib}")
endif()

# Compiles the backends' object libraries into `target` (the core). They are private and not
# installed, so the link is build-tree only; in the package, a static core names the backends'
# own links (Highway, OpenMP) itself, and a shared one has them inside. The CUDA runtime is the
# exception: the package carries its own copy (lidar_sgm::cuda_runtime, see
# lidar_sgm_install_package), so that a user without the CUDA toolkit can still link a static core.
function(lidar_sgm_link_backends target)
  foreach(backend IN LISTS ARGN)
    target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:${backend}>)
    get_target_property(backend_links ${backend} INTERFACE_LINK_LIBRARIES)
    if(backend_links)
      foreach(link IN LISTS backend_links)
        if(link STREQUAL "CUDA::cudart_static")
          set(link lidar_sgm::cuda_runtime)
        endif()
        target_link_libraries(${target} PRIVATE $<INSTALL_INTERFACE:${link}>)
      endforeach()
    endif()
  endforeach()
endfunction()

# Absolute include directories of third-party packages (OpenCV's, PCL's) that the targets name
# for the build tree: downstream, the dependencies' own imported targets (opencv_core,
# pcl_common), which the Config finds again, carry them. Exporting the paths would pin the package
# to the layout of the machine it was built on.
function(_lidar_sgm_build_only_absolute_includes target property)
  get_target_property(dirs ${target} ${property})
  if(NOT dirs)
    return()
  endif()
  set(rewritten "")
  foreach(dir IN LISTS dirs)
    if(IS_ABSOLUTE "${dir}")
      list(APPEND rewritten "$<BUILD_INTERFACE:${dir}>")
    else()
      list(APPEND rewritten "${dir}")
    endif()
  endforeach()
  set_property(TARGET ${target} PROPERTY ${property} "${rewritten}")
endfunction()

# Installs the library target of `component` (lidar_sgm_<component>) as lidar_sgm::<component>,
# with its public headers (include/lidar_sgm/<component>/, minus `EXCLUDE`d files).
function(_lidar_sgm_install_component component)
  cmake_parse_arguments(ARG "" "" "EXCLUDE" ${ARGN})
  set(target lidar_sgm_${component})
  set_target_properties(${target} PROPERTIES
    EXPORT_NAME ${component}
    VERSION ${PROJECT_VERSION}
    SOVERSION ${LIDAR_SGM_SOVERSION})
  _lidar_sgm_build_only_absolute_includes(${target} INTERFACE_INCLUDE_DIRECTORIES)
  _lidar_sgm_build_only_absolute_includes(${target} INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
  # The build-tree include directories are absolute too (BUILD_INTERFACE already); the installed
  # headers live in <prefix>/include.
  target_include_directories(${target} PUBLIC $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  install(TARGETS ${target} EXPORT lidar_sgm_${component}Targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(EXPORT lidar_sgm_${component}Targets
    NAMESPACE lidar_sgm::
    DESTINATION ${LIDAR_SGM_INSTALL_CMAKEDIR})
  set(excludes "")
  foreach(file IN LISTS ARG_EXCLUDE)
    list(APPEND excludes PATTERN ${file} EXCLUDE)
  endforeach()
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/lidar_sgm/${component}
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lidar_sgm
    FILES_MATCHING PATTERN "*.hpp" ${excludes})
endfunction()

# Installs every public library that this configuration built, the version header, the CMake
# package and lidar_sgm.pc. Called once, at the end of the top-level CMakeLists.txt (after every
# target exists).
function(lidar_sgm_install_package)
  set(built "")
  foreach(component IN LISTS LIDAR_SGM_PACKAGE_COMPONENTS)
    if(NOT TARGET lidar_sgm_${component})
      continue()
    endif()
    set(exclude "")
    if(component STREQUAL "io" AND NOT LIDAR_SGM_HAVE_PCL)
      # Their definitions are compiled only with PCL (src/io/CMakeLists.txt).
      set(exclude cloud_io.hpp pcl_image.hpp)
    endif()
    _lidar_sgm_install_component(${component} EXCLUDE ${exclude})
    list(APPEND built ${component})
  endforeach()

  install(FILES ${PROJECT_BINARY_DIR}/include/lidar_sgm/version.hpp
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lidar_sgm)

  # What the Config must find again for the targets to resolve downstream. A static core carries
  # the fast backend's links (Highway, OpenMP) to whoever links it; a shared one has them inside.
  # (lidar_sgm_link_backends names them as $<INSTALL_INTERFACE:...> links; the imported targets
  # themselves are visible only in the backend's folder.)
  get_target_property(core_type lidar_sgm_core TYPE)
  get_target_property(core_links lidar_sgm_core LINK_LIBRARIES)
  set(LIDAR_SGM_CORE_NEEDS_HWY OFF)
  set(LIDAR_SGM_CORE_NEEDS_OPENMP OFF)
  set(LIDAR_SGM_CORE_NEEDS_CUDA OFF)
  if(core_type STREQUAL "STATIC_LIBRARY")
    if("$<INSTALL_INTERFACE:lidar_sgm::cuda_runtime>" IN_LIST core_links)
      set(LIDAR_SGM_CORE_NEEDS_CUDA ON)
    endif()
    if("$<INSTALL_INTERFACE:hwy::hwy>" IN_LIST core_links)
      set(LIDAR_SGM_CORE_NEEDS_HWY ON)
    endif()
    if("$<INSTALL_INTERFACE:OpenMP::OpenMP_CXX>" IN_LIST core_links)
      set(LIDAR_SGM_CORE_NEEDS_OPENMP ON)
    endif()
  endif()
  # A static core with the cuda backend needs the static CUDA runtime wherever it is linked. The
  # package ships the copy it was built with (NVIDIA lists libcudart_static.a as redistributable):
  # a CPU-only user, on a machine without the toolkit, then configures and links as anyone else,
  # and the runtime matches the kernels' toolkit. A shared core has the runtime inside.
  set(LIDAR_SGM_CUDA_RUNTIME_DIR "${CMAKE_INSTALL_LIBDIR}/lidar_sgm")
  if(LIDAR_SGM_CORE_NEEDS_CUDA)
    find_package(CUDAToolkit QUIET)
    if(NOT CUDA_cudart_static_LIBRARY)
      message(FATAL_ERROR "lidar_sgm: the static core links the CUDA runtime, but libcudart_static was not found")
    endif()
    install(FILES "${CUDA_cudart_static_LIBRARY}" DESTINATION "${LIDAR_SGM_CUDA_RUNTIME_DIR}"
      RENAME libcudart_static.a)
  endif()
  set(LIDAR_SGM_BUILT_COMPONENTS "${built}")
  set(LIDAR_SGM_EIGEN3_VERSION "${Eigen3_VERSION}")
  set(LIDAR_SGM_OPENCV_VERSION "${OpenCV_VERSION_MAJOR}.${OpenCV_VERSION_MINOR}")
  set(LIDAR_SGM_PCL_VERSION "${PCL_VERSION_MAJOR}.${PCL_VERSION_MINOR}")

  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/lidar_sgmConfig.cmake.in
    ${PROJECT_BINARY_DIR}/lidar_sgmConfig.cmake
    INSTALL_DESTINATION ${LIDAR_SGM_INSTALL_CMAKEDIR}
    PATH_VARS LIDAR_SGM_CUDA_RUNTIME_DIR)
  # 0.x: a minor release may break the API, so 0.1 must not satisfy a request for 0.2, nor 0.2 one
  # for 0.1 (SameMinorVersion); from 1.0 on, SameMajorVersion is the promise.
  if(PROJECT_VERSION_MAJOR EQUAL 0)
    set(compatibility SameMinorVersion)
  else()
    set(compatibility SameMajorVersion)
  endif()
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/lidar_sgmConfigVersion.cmake
    VERSION ${PROJECT_VERSION}
    COMPATIBILITY ${compatibility})
  install(FILES ${PROJECT_BINARY_DIR}/lidar_sgmConfig.cmake ${PROJECT_BINARY_DIR}/lidar_sgmConfigVersion.cmake
    DESTINATION ${LIDAR_SGM_INSTALL_CMAKEDIR})

  # pkg-config for the core (C++17 and the standard library only). A static core (the default)
  # is linked by its user together with the fast backend's Highway and OpenMP and the cuda
  # backend's runtime (the package's copy): they go into Requires and Libs, so that a plain
  # `pkg-config --libs lidar_sgm` links. A shared core has them inside and names nothing else.
  set(pc_requires "")
  set(pc_libs "")
  if(LIDAR_SGM_CORE_NEEDS_HWY)
    set(pc_requires "libhwy")
  endif()
  if(LIDAR_SGM_CORE_NEEDS_OPENMP)
    set(pc_libs "-fopenmp")
  endif()
  if(LIDAR_SGM_CORE_NEEDS_CUDA)
    # The static CUDA runtime and what it needs from the system.
    string(APPEND pc_libs " -L\${libdir}/lidar_sgm -lcudart_static -ldl -lrt -lpthread")
  endif()
  string(STRIP "${pc_libs}" pc_libs)
  set(LIDAR_SGM_PC_REQUIRES "${pc_requires}")
  set(LIDAR_SGM_PC_LIBS "${pc_libs}")
  # The prefix is found from the .pc file's own place, so `cmake --install --prefix P` (which the
  # configure step never saw) and a moved prefix both work; absolute install dirs stay absolute.
  if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
    set(LIDAR_SGM_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  else()
    file(RELATIVE_PATH pc_to_prefix "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
    string(REGEX REPLACE "/$" "" pc_to_prefix "${pc_to_prefix}")
    set(LIDAR_SGM_PC_PREFIX "\${pcfiledir}/${pc_to_prefix}")
  endif()
  foreach(dir LIBDIR INCLUDEDIR)
    if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
      set(LIDAR_SGM_PC_${dir} "${CMAKE_INSTALL_${dir}}")
    else()
      set(LIDAR_SGM_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
    endif()
  endforeach()
  configure_file(${PROJECT_SOURCE_DIR}/cmake/lidar_sgm.pc.in ${PROJECT_BINARY_DIR}/lidar_sgm.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/lidar_sgm.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()
