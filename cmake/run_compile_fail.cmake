# Driver for walkgen_add_compile_fail_test (cmake -P). Builds one target that must NOT compile
# and checks that the compiler said what we expect.
#   -DBUILD_DIR=<build tree> -DTARGET=<target> [-DCONFIG=<config>] -DREGEX=<expected message regex>
foreach(_var BUILD_DIR TARGET REGEX)
  if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "run_compile_fail.cmake: -D${_var}=... is required")
  endif()
endforeach()

set(_config_args "")
if(CONFIG)
  set(_config_args --config "${CONFIG}")
endif()

execute_process(
  COMMAND "${CMAKE_COMMAND}" --build "${BUILD_DIR}" --target "${TARGET}" ${_config_args}
  RESULT_VARIABLE _rc
  OUTPUT_VARIABLE _out
  ERROR_VARIABLE _out)

if(_rc EQUAL 0)
  message(FATAL_ERROR "compile-fail test '${TARGET}': the source compiled, but it must be rejected "
                      "with a message matching '${REGEX}'.\n${_out}")
endif()
string(REGEX REPLACE "[ \t\r\n]+" " " _flat "${_out}")  # in case the message was wrapped
if(NOT _out MATCHES "${REGEX}" AND NOT _flat MATCHES "${REGEX}")
  message(FATAL_ERROR "compile-fail test '${TARGET}': compilation failed as expected, but not with "
                      "a message matching '${REGEX}'. Compiler output:\n${_out}")
endif()
message(STATUS "compile-fail test '${TARGET}': rejected as expected (matched '${REGEX}')")
