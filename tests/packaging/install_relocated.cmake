# ctest "install_relocated", script mode:
#   cmake -DINSTALL_FROM=<walkgen build dir> -DWORK=<scratch dir> -DSOURCE_DIR=<walkgen source>
#         -DGENERATOR=... [-DCONFIG -DCXX_COMPILER -DCXX_FLAGS -DMAKE_PROGRAM -DEIGEN3_DIR]
#         -P tests/packaging/install_relocated.cmake
# 1. `cmake --install` the build tree into WORK/prefix;
# 2. no installed text file names the source or build tree (an absolute path fixed at configure
#    time would break a moved install);
# 3. moves WORK/prefix to WORK/moved (the original is gone);
# 4. builds tests/packaging/relocated_consumer against WORK/moved through
#    find_package(walkgen COMPONENTS simulation) (which brings mujoco, ceres, urdf) and runs it: data_dir() is the moved
#    share/walkgen, the default robot loads, and the closed loop walks it for one second.
foreach(_var INSTALL_FROM WORK SOURCE_DIR GENERATOR)
  if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "install_relocated.cmake: -D${_var}=... is required")
  endif()
endforeach()
set(_driver "${CMAKE_CURRENT_LIST_DIR}/run_consumer.cmake")
set(_prefix "${WORK}/prefix")
set(_moved "${WORK}/moved")
file(REMOVE_RECURSE "${_prefix}" "${_moved}")

execute_process(COMMAND "${CMAKE_COMMAND}" "-DINSTALL_FROM=${INSTALL_FROM}" "-DPREFIX=${_prefix}"
                        "-DCONFIG=${CONFIG}" -P "${_driver}"
                RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "install_relocated: installing into ${_prefix} failed")
endif()

# Text files only: headers, CMake files, YAML, URDF, MJCF, Markdown.
file(GLOB_RECURSE _installed "${_prefix}/*.hpp" "${_prefix}/*.h" "${_prefix}/*.cmake"
     "${_prefix}/*.yaml" "${_prefix}/*.urdf" "${_prefix}/*.xml" "${_prefix}/*.md")
list(LENGTH _installed _count)
if(_count EQUAL 0)
  message(FATAL_ERROR "install_relocated: no text files installed under ${_prefix}")
endif()
get_filename_component(_source_real "${SOURCE_DIR}" REALPATH)
get_filename_component(_build_real "${INSTALL_FROM}" REALPATH)
set(_offenders "")
foreach(_f IN LISTS _installed)
  file(READ "${_f}" _text)
  foreach(_tree "${SOURCE_DIR}" "${_source_real}" "${INSTALL_FROM}" "${_build_real}")
    string(FIND "${_text}" "${_tree}" _pos)
    if(NOT _pos EQUAL -1)
      list(APPEND _offenders "${_f} (names ${_tree})")
      break()
    endif()
  endforeach()
endforeach()
if(_offenders)
  string(REPLACE ";" "\n  " _lines "${_offenders}")
  message(FATAL_ERROR "install_relocated: installed files name the source or build tree:\n"
                      "  ${_lines}")
endif()
message(STATUS "install_relocated: ${_count} installed text files name no source or build path")

file(RENAME "${_prefix}" "${_moved}")
if(EXISTS "${_prefix}")
  message(FATAL_ERROR "install_relocated: ${_prefix} still exists after the move")
endif()
message(STATUS "install_relocated: moved ${_prefix} to ${_moved}")

# The consumer must not find the data through the environment.
unset(ENV{WALKGEN_DATA_DIR})
execute_process(COMMAND "${CMAKE_COMMAND}"
                        "-DSOURCE=${CMAKE_CURRENT_LIST_DIR}/relocated_consumer"
                        "-DBUILD=${WORK}/relocated_consumer" "-DPREFIX=${_moved}"
                        "-DGENERATOR=${GENERATOR}" "-DCONFIG=${CONFIG}"
                        "-DCXX_COMPILER=${CXX_COMPILER}" "-DCXX_FLAGS=${CXX_FLAGS}"
                        "-DMAKE_PROGRAM=${MAKE_PROGRAM}" "-DEIGEN3_DIR=${EIGEN3_DIR}"
                        "-DEXPECTED_DATA_DIR=${_moved}/share/walkgen"
                        -P "${_driver}"
                RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "install_relocated: the consumer of the moved installation failed")
endif()
message(STATUS "install_relocated: the consumer walked the default robot from ${_moved}")
