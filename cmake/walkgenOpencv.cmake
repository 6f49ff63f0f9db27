# Finds OpenCV for walkgen's stereo depth adapter (walkgen::opencv). Included by the top-level
# CMakeLists.txt. The adapter needs the modules below, ximgproc (the WLS disparity filter) among
# them, which Debian ships in libopencv-contrib-dev next to libopencv-dev. Sets
#   WALKGEN_OPENCV_FOUND        OpenCV with every module in WALKGEN_OPENCV_MODULES was found
#   WALKGEN_OPENCV_MODULES      the OpenCV modules (targets opencv_<module>) the adapter links
include_guard(GLOBAL)

set(WALKGEN_OPENCV_MODULES core imgproc imgcodecs calib3d ximgproc)
set(WALKGEN_OPENCV_FOUND OFF)
if(NOT DEFINED WALKGEN_WITH_OPENCV OR WALKGEN_WITH_OPENCV)
  find_package(OpenCV CONFIG QUIET COMPONENTS ${WALKGEN_OPENCV_MODULES})
  if(OpenCV_FOUND)
    set(WALKGEN_OPENCV_FOUND ON)
  endif()
endif()

# The shared data set of the OpenCV tests, benchmark and examples (OpenCV's stereo chessboards,
# Middlebury Aloe and Cones; each folder has a SOURCE.txt with its origin and licence): the copy in
# tests/data (3.2 MB), so that a fresh clone tests without anything beside it.
set(WALKGEN_TEST_DATA_DIR "${CMAKE_CURRENT_LIST_DIR}/../tests/data"
    CACHE PATH "walkgen's stereo test data: chessboards, Middlebury Aloe and Cones")
get_filename_component(WALKGEN_TEST_DATA_DIR "${WALKGEN_TEST_DATA_DIR}" ABSOLUTE)
