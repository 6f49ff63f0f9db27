# Driver for the packaging tests (cmake -P). Two modes:
#
# Install the walkgen build tree into a fresh prefix:
#   -DINSTALL_FROM=<walkgen build dir> -DPREFIX=<prefix> [-DCONFIG=<config>]
#   With -DCONFIGURE_FROM=<walkgen source>, INSTALL_FROM is first configured afresh from that source
#   (with -DGENERATOR and the optional compiler settings below, as a consumer is, plus
#   -DCONFIGURE_ARGS=<-DNAME=VALUE|...>) and built.
#
# Configure, build and run a consumer project (from a fresh build dir):
#   -DSOURCE=<consumer dir> -DBUILD=<its build dir> -DGENERATOR=<generator> [-DCONFIG=<config>]
#   and either -DPREFIX=<walkgen install prefix> (find_package) or -DWALKGEN_SOURCE_DIR=<dir>
#   (add_subdirectory). Optional: -DCXX_COMPILER -DCXX_FLAGS -DMAKE_PROGRAM -DEIGEN3_DIR,
#   -DCOMPONENT=<name> (forwarded as WALKGEN_COMPONENT), -DEXPECTED_DATA_DIR=<dir> (forwarded), and -DEXPECT_CONFIGURE_FAILURE=<regex>:
#   then the configure step must fail with output matching <regex>, and nothing is built.
# The consumer's program must be called walkgen_consumer and exit 0.

function(_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  message("---- ${what}\n${_out}")
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "packaging test: ${what} failed (exit ${_rc})")
  endif()
endfunction()

# This build's settings, forwarded to every configure as -D<cache variable>=<value> where given.
set(_build_settings CONFIG:CMAKE_BUILD_TYPE CXX_COMPILER:CMAKE_CXX_COMPILER
                    CXX_FLAGS:CMAKE_CXX_FLAGS MAKE_PROGRAM:CMAKE_MAKE_PROGRAM EIGEN3_DIR:Eigen3_DIR)
# Sets `out` to -D<cache variable>=<value> for each <variable>:<cache variable> that was given.
function(_forward out)
  set(_args "")
  foreach(_pair IN LISTS ARGN)
    string(REPLACE ":" ";" _pair "${_pair}")
    list(GET _pair 0 _in)
    list(GET _pair 1 _cache)
    if(NOT "${${_in}}" STREQUAL "")
      list(APPEND _args "-D${_cache}=${${_in}}")
    endif()
  endforeach()
  set(${out} ${_args} PARENT_SCOPE)
endfunction()

set(_config_args "")
if(CONFIG)
  set(_config_args --config "${CONFIG}")
endif()

# --- Install mode --------------------------------------------------------------------------------
if(DEFINED INSTALL_FROM)
  if(NOT PREFIX)
    message(FATAL_ERROR "run_consumer.cmake: -DPREFIX=... is required with -DINSTALL_FROM")
  endif()
  file(REMOVE_RECURSE "${PREFIX}")
  if(CONFIGURE_FROM)
    file(REMOVE_RECURSE "${INSTALL_FROM}")
    _forward(_forwarded ${_build_settings})
    string(REPLACE "|" ";" _extra "${CONFIGURE_ARGS}")
    _step("configure ${CONFIGURE_FROM} into ${INSTALL_FROM}" "${CMAKE_COMMAND}"
          -S "${CONFIGURE_FROM}" -B "${INSTALL_FROM}" -G "${GENERATOR}" ${_forwarded} ${_extra})
    _step("build ${INSTALL_FROM}" "${CMAKE_COMMAND}" --build "${INSTALL_FROM}" ${_config_args})
  endif()
  _step("install ${INSTALL_FROM} into ${PREFIX}"
        "${CMAKE_COMMAND}" --install "${INSTALL_FROM}" --prefix "${PREFIX}" ${_config_args})
  file(GLOB_RECURSE _configs "${PREFIX}/*/walkgenConfig.cmake")
  if(NOT _configs OR NOT EXISTS "${PREFIX}/include/walkgen/walkgen.hpp")
    message(FATAL_ERROR "packaging test: the install into ${PREFIX} lacks walkgenConfig.cmake "
                        "or include/walkgen/walkgen.hpp")
  endif()
  message(STATUS "installed walkgen into ${PREFIX} (${_configs})")
  return()
endif()

# --- Consumer mode -------------------------------------------------------------------------------
foreach(_var SOURCE BUILD GENERATOR)
  if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "run_consumer.cmake: -D${_var}=... is required")
  endif()
endforeach()
if(NOT PREFIX AND NOT WALKGEN_SOURCE_DIR)
  message(FATAL_ERROR "run_consumer.cmake: pass -DPREFIX=... or -DWALKGEN_SOURCE_DIR=...")
endif()

_forward(_forwarded ${_build_settings} PREFIX:CMAKE_PREFIX_PATH
         WALKGEN_SOURCE_DIR:WALKGEN_SOURCE_DIR COMPONENT:WALKGEN_COMPONENT
         EXPECTED_DATA_DIR:EXPECTED_DATA_DIR)
set(_args -S "${SOURCE}" -B "${BUILD}" -G "${GENERATOR}" ${_forwarded})

file(REMOVE_RECURSE "${BUILD}")

if(DEFINED EXPECT_CONFIGURE_FAILURE)
  execute_process(COMMAND "${CMAKE_COMMAND}" ${_args}
                  RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  message("---- configure ${SOURCE} (expected to fail)\n${_out}")
  if(_rc EQUAL 0)
    message(FATAL_ERROR "packaging test: configuring ${SOURCE} succeeded, but it must fail with "
                        "a message matching '${EXPECT_CONFIGURE_FAILURE}'")
  endif()
  # CMake word-wraps its messages, so match with all whitespace runs collapsed to one space.
  string(REGEX REPLACE "[ \t\r\n]+" " " _flat "${_out}")
  if(NOT _flat MATCHES "${EXPECT_CONFIGURE_FAILURE}")
    message(FATAL_ERROR "packaging test: configuring ${SOURCE} failed as expected, but without a "
                        "message matching '${EXPECT_CONFIGURE_FAILURE}'")
  endif()
  message(STATUS "configure failed as expected (matched '${EXPECT_CONFIGURE_FAILURE}')")
  return()
endif()

_step("configure ${SOURCE}" "${CMAKE_COMMAND}" ${_args})

# find_package must have picked up the freshly installed package, not some other walkgen.
if(PREFIX)
  file(STRINGS "${BUILD}/CMakeCache.txt" _dir_line REGEX "^walkgen_DIR:")
  string(REGEX REPLACE "^walkgen_DIR:[A-Z]+=" "" _walkgen_dir "${_dir_line}")
  get_filename_component(_real_prefix "${PREFIX}" REALPATH)
  get_filename_component(_real_walkgen_dir "${_walkgen_dir}" REALPATH)
  string(FIND "${_real_walkgen_dir}/" "${_real_prefix}/" _pos)
  if(NOT _pos EQUAL 0)
    message(FATAL_ERROR "packaging test: the consumer found walkgen in '${_walkgen_dir}', "
                        "not in the test prefix '${PREFIX}'")
  endif()
endif()

_step("build ${BUILD}" "${CMAKE_COMMAND}" --build "${BUILD}" ${_config_args})

# Single-config generators put the program in BUILD, multi-config ones in BUILD/<config>.
set(_exe "")
foreach(_candidate "${BUILD}/walkgen_consumer" "${BUILD}/${CONFIG}/walkgen_consumer"
                   "${BUILD}/walkgen_consumer.exe" "${BUILD}/${CONFIG}/walkgen_consumer.exe")
  if(EXISTS "${_candidate}" AND NOT IS_DIRECTORY "${_candidate}")
    set(_exe "${_candidate}")
    break()
  endif()
endforeach()
if(NOT _exe)
  message(FATAL_ERROR "packaging test: walkgen_consumer was not found in ${BUILD}")
endif()
_step("run ${_exe}" "${_exe}")
