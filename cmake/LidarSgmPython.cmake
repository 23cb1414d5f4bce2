# Finds what the Python package needs (the interpreter, its development files, pybind11) and sets
# LIDAR_SGM_PYTHON_MISSING to what is not found ("" when all is).
#
# The package and its tests import numpy, which Debian installs for /usr/bin/python3. Another
# python3 that comes first on the PATH (pyenv, a virtual environment) may lack it; unless
# Python3_EXECUTABLE is given, the first of PATH's python3 and /usr/bin/python3 that imports numpy
# is used.
if(NOT Python3_EXECUTABLE)
  find_program(_lidar_sgm_path_python3 NAMES python3)
  foreach(candidate IN ITEMS "${_lidar_sgm_path_python3}" /usr/bin/python3)
    if(candidate AND EXISTS "${candidate}")
      execute_process(COMMAND "${candidate}" -c "import numpy" RESULT_VARIABLE numpy_missing OUTPUT_QUIET ERROR_QUIET)
      if(numpy_missing EQUAL 0)
        set(Python3_EXECUTABLE "${candidate}" CACHE FILEPATH "The Python 3 interpreter the package is built for")
        break()
      endif()
    endif()
  endforeach()
  unset(_lidar_sgm_path_python3 CACHE)
endif()

find_package(Python3 3.7 QUIET COMPONENTS Interpreter Development.Module)
if(Python3_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)
endif()
set(LIDAR_SGM_PYTHON_MISSING "")
if(NOT Python3_FOUND)
  set(LIDAR_SGM_PYTHON_MISSING "the Python 3 development files (Debian: python3-dev)")
elseif(NOT pybind11_FOUND)
  set(LIDAR_SGM_PYTHON_MISSING "pybind11 (Debian: pybind11-dev)")
elseif(NOT TARGET lidar_sgm_apps_densify)
  set(LIDAR_SGM_PYTHON_MISSING "lidar_sgm_densify's dependencies (OpenCV, PCL, CLI11)")
endif()
