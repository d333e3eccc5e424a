# Finds MuJoCo's C library and headers, as shipped in the PyPI `mujoco` 3.3.x wheel
# (`scripts/install-deps.sh` installs it into the Python interpreter the build uses).
# Debian 12's libmujoco-dev is 2.2.2, without mjSpec, which upkie-rl builds its model with.
#
# Looks in MUJOCO_ROOT (a directory holding libmujoco.so* and include/mujoco/mujoco.h),
# else in the `mujoco` package of Python_EXECUTABLE. Defines MuJoCo_FOUND,
# MuJoCo_VERSION, MuJoCo_LIBRARY_DIR and the imported target MuJoCo::mujoco.

set(MUJOCO_ROOT "" CACHE PATH "Directory with libmujoco.so and include/mujoco/mujoco.h")
set(_mujoco_hints ${MUJOCO_ROOT})
if(NOT MUJOCO_ROOT)
  if(NOT Python_EXECUTABLE)
    find_package(Python COMPONENTS Interpreter QUIET)
  endif()
  if(Python_EXECUTABLE)
    execute_process(
      COMMAND ${Python_EXECUTABLE} -c "import mujoco, os; print(os.path.dirname(mujoco.__file__))"
      OUTPUT_VARIABLE _mujoco_package_dir OUTPUT_STRIP_TRAILING_WHITESPACE
      RESULT_VARIABLE _mujoco_status ERROR_QUIET)
    if(_mujoco_status EQUAL 0)
      list(APPEND _mujoco_hints ${_mujoco_package_dir})
    endif()
  endif()
endif()

find_path(MuJoCo_INCLUDE_DIR mujoco/mujoco.h HINTS ${_mujoco_hints} PATH_SUFFIXES include
  NO_DEFAULT_PATH)
# The wheel ships only the versioned file (libmujoco.so.3.3.7).
find_file(MuJoCo_LIBRARY NAMES libmujoco.so HINTS ${_mujoco_hints} NO_DEFAULT_PATH)
if(NOT MuJoCo_LIBRARY)
  file(GLOB _mujoco_candidates LIST_DIRECTORIES false
    "${MUJOCO_ROOT}/libmujoco.so.*" "${_mujoco_package_dir}/libmujoco.so.*")
  if(_mujoco_candidates)
    list(GET _mujoco_candidates 0 _mujoco_first)
    set(MuJoCo_LIBRARY "${_mujoco_first}" CACHE FILEPATH "MuJoCo shared library" FORCE)
  endif()
endif()

if(MuJoCo_INCLUDE_DIR AND EXISTS "${MuJoCo_INCLUDE_DIR}/mujoco/mujoco.h")
  file(STRINGS "${MuJoCo_INCLUDE_DIR}/mujoco/mujoco.h" _mujoco_version_line
    REGEX "^#define mjVERSION_HEADER [0-9]+")
  string(REGEX REPLACE ".*mjVERSION_HEADER ([0-9]+).*" "\\1" _mujoco_version_number
    "${_mujoco_version_line}")
  if(_mujoco_version_number)
    math(EXPR _major "${_mujoco_version_number} / 100")
    math(EXPR _minor "(${_mujoco_version_number} % 100) / 10")
    math(EXPR _patch "${_mujoco_version_number} % 10")
    set(MuJoCo_VERSION "${_major}.${_minor}.${_patch}")
  endif()
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MuJoCo
  REQUIRED_VARS MuJoCo_LIBRARY MuJoCo_INCLUDE_DIR
  VERSION_VAR MuJoCo_VERSION)

if(MuJoCo_FOUND AND NOT TARGET MuJoCo::mujoco)
  get_filename_component(MuJoCo_LIBRARY_DIR "${MuJoCo_LIBRARY}" DIRECTORY)
  add_library(MuJoCo::mujoco SHARED IMPORTED)
  set_target_properties(MuJoCo::mujoco PROPERTIES
    IMPORTED_LOCATION "${MuJoCo_LIBRARY}"
    IMPORTED_NO_SONAME FALSE
    INTERFACE_INCLUDE_DIRECTORIES "${MuJoCo_INCLUDE_DIR}")
endif()
