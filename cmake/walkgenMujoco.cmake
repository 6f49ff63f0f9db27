# Finds MuJoCo and EGL for walkgen's MuJoCo adapter and for the tests that use MuJoCo as a
# reference. Included by the top-level CMakeLists.txt and by tests/CMakeLists.txt.
#
# Debian's MuJoCo 2.2.2 CMake package names /usr/include/libqhull_r, which the package does not
# install, so MuJoCo's header and library are looked up directly. Sets (cache):
#   WALKGEN_MUJOCO_INCLUDE_DIR, WALKGEN_MUJOCO_LIBRARY   MuJoCo (Debian: libmujoco-dev)
#   WALKGEN_EGL_INCLUDE_DIR, WALKGEN_EGL_LIBRARY         EGL (Debian: libegl-dev) for offscreen
#                                                        rendering of the cameras
# and WALKGEN_MUJOCO_FOUND (MuJoCo and EGL both found).
include_guard(GLOBAL)

find_path(WALKGEN_MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
find_library(WALKGEN_MUJOCO_LIBRARY mujoco)
find_path(WALKGEN_EGL_INCLUDE_DIR EGL/egl.h)
find_library(WALKGEN_EGL_LIBRARY EGL)

set(WALKGEN_MUJOCO_FOUND OFF)
if(WALKGEN_MUJOCO_INCLUDE_DIR AND WALKGEN_MUJOCO_LIBRARY AND WALKGEN_EGL_INCLUDE_DIR
   AND WALKGEN_EGL_LIBRARY)
  set(WALKGEN_MUJOCO_FOUND ON)
endif()

# walkgen_mujoco_missing(<var>): the Debian packages to install, for error messages.
function(walkgen_mujoco_missing out)
  set(_missing "")
  if(NOT WALKGEN_MUJOCO_INCLUDE_DIR OR NOT WALKGEN_MUJOCO_LIBRARY)
    list(APPEND _missing libmujoco-dev)
  endif()
  if(NOT WALKGEN_EGL_INCLUDE_DIR OR NOT WALKGEN_EGL_LIBRARY)
    list(APPEND _missing libegl-dev libegl-mesa0)
  endif()
  string(REPLACE ";" " " _missing "${_missing}")
  set(${out} "${_missing}" PARENT_SCOPE)
endfunction()
