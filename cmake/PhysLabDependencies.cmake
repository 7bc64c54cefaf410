# Every dependency is a Debian package; a missing one stops configuration with its package name.

function(physlab_missing what package)
  message(FATAL_ERROR "PhysLab needs ${what}. Install it with `./physlab setup` "
                      "(or: sudo apt-get install ${package}).")
endfunction()

find_package(Eigen3 3.4 CONFIG QUIET)
if(NOT Eigen3_FOUND)
  physlab_missing("Eigen 3.4" libeigen3-dev)
endif()

find_package(Catch2 2.13 CONFIG QUIET)
if(NOT Catch2_FOUND)
  physlab_missing("Catch2 2.13" catch2)
endif()
include(Catch)

find_program(GNUPLOT_EXECUTABLE gnuplot)
if(NOT GNUPLOT_EXECUTABLE)
  physlab_missing("gnuplot (to draw the charts)" gnuplot-nox)
endif()

find_package(Threads REQUIRED)

# Whether the peers that are C++ libraries (Bullet, FCL) can be linked: a Linux distribution
# builds them for libstdc++, so a libc++ build of the benchmarks leaves them out (macOS's are
# built for libc++, its only standard library).
include(CheckCXXSourceCompiles)
set(CMAKE_REQUIRED_QUIET ON)
check_cxx_source_compiles("#include <ciso646>
#ifndef _LIBCPP_VERSION
#error not libc++
#endif
int main() { return 0; }" PHYSLAB_LIBCXX)
unset(CMAKE_REQUIRED_QUIET)
set(PHYSLAB_CXX_PEERS ON)
if(PHYSLAB_LIBCXX AND CMAKE_SYSTEM_NAME STREQUAL "Linux")
  set(PHYSLAB_CXX_PEERS OFF)
  message(STATUS "libc++: the benchmarks compare with no C++ peer (Bullet, FCL: built for libstdc++)")
endif()

# Optional peer for benchmarks: Bullet's double-precision build (never needed to build or test).
# Links it into `target` with PHYSLAB_HAVE_BULLET defined when pkg-config finds it (and the
# standard library is the one it was built for: PHYSLAB_CXX_PEERS).
function(physlab_link_bullet target)
  find_package(PkgConfig QUIET)
  if(NOT PKG_CONFIG_FOUND OR NOT PHYSLAB_CXX_PEERS)
    return()
  endif()
  if(NOT TARGET PkgConfig::PHYSLAB_BULLET)
    pkg_check_modules(PHYSLAB_BULLET QUIET IMPORTED_TARGET GLOBAL bullet-float64)
  endif()
  if(TARGET PkgConfig::PHYSLAB_BULLET)
    target_link_libraries(${target} PRIVATE PkgConfig::PHYSLAB_BULLET)
    target_compile_definitions(${target} PRIVATE PHYSLAB_HAVE_BULLET)
    message(STATUS "${target}: comparing with Bullet (bullet-float64)")
  endif()
endfunction()

# Optional peer for benchmarks: MuJoCo (libmujoco-dev). Links it into `target` with
# PHYSLAB_HAVE_MUJOCO defined when its header and library are found. Debian's mujocoConfig.cmake
# (2.2.2) names a missing include folder (/usr/include/libqhull_r), which makes configuration
# fail, so the header and library are looked up directly instead.
function(physlab_link_mujoco target)
  find_path(PHYSLAB_MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
  find_library(PHYSLAB_MUJOCO_LIBRARY mujoco)
  if(PHYSLAB_MUJOCO_INCLUDE_DIR AND PHYSLAB_MUJOCO_LIBRARY)
    target_include_directories(${target} SYSTEM PRIVATE "${PHYSLAB_MUJOCO_INCLUDE_DIR}")
    target_link_libraries(${target} PRIVATE "${PHYSLAB_MUJOCO_LIBRARY}")
    target_compile_definitions(${target} PRIVATE PHYSLAB_HAVE_MUJOCO)
    message(STATUS "${target}: comparing with MuJoCo (${PHYSLAB_MUJOCO_LIBRARY})")
  endif()
endfunction()
