# ctest "examples_help", script mode:
#   cmake -DPROGRAMS="<exe>|<exe>|..." -P tests/examples_help.cmake
# Each example program must
#   - answer --help with exit status 0 and a usage text ("Usage:" and an "Options:" section that
#     lists --help), printed on stdout;
#   - reject an unknown option with a non-zero exit status and exactly one line on stderr that
#     names the option.
if(NOT PROGRAMS)
  message(FATAL_ERROR "examples_help: PROGRAMS is empty (no example was built)")
endif()
string(REPLACE "|" ";" _programs "${PROGRAMS}")
set(_failures "")
set(_count 0)
foreach(_exe IN LISTS _programs)
  get_filename_component(_name "${_exe}" NAME)
  math(EXPR _count "${_count} + 1")
  execute_process(COMMAND "${_exe}" --help RESULT_VARIABLE _rc OUTPUT_VARIABLE _out
                  ERROR_VARIABLE _err TIMEOUT 30)
  if(NOT _rc EQUAL 0)
    list(APPEND _failures "${_name} --help: exit status ${_rc} (expected 0); stderr: ${_err}")
  elseif(NOT _out MATCHES "Usage:" OR NOT _out MATCHES "Options:" OR NOT _out MATCHES "--help")
    list(APPEND _failures "${_name} --help: no usage text on stdout (expected \"Usage:\" and "
                          "\"Options:\"), got: ${_out}")
  endif()
  execute_process(COMMAND "${_exe}" --no-such-option-xyz RESULT_VARIABLE _rc
                  OUTPUT_VARIABLE _out ERROR_VARIABLE _err TIMEOUT 30)
  string(STRIP "${_err}" _err)
  string(REGEX MATCHALL "\n" _newlines "${_err}")
  list(LENGTH _newlines _extra_lines)
  if(_rc EQUAL 0)
    list(APPEND _failures "${_name} --no-such-option-xyz: exit status 0 (expected non-zero)")
  elseif(NOT _err MATCHES "no-such-option-xyz" OR NOT _extra_lines EQUAL 0)
    list(APPEND _failures "${_name} --no-such-option-xyz: expected one line on stderr naming the "
                          "option, got: '${_err}'")
  endif()
endforeach()
if(_failures)
  list(LENGTH _failures _n)
  string(REPLACE ";" "\n  " _lines "${_failures}")
  message(FATAL_ERROR "examples_help: ${_n} problem(s) in ${_count} programs:\n  ${_lines}")
endif()
message(STATUS "examples_help: ${_count} programs answer --help and reject an unknown option")
