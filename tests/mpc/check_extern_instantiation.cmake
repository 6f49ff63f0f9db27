# ctest "walking_mpc_16_extern" (script mode): the object files compiled through the extern
# header walkgen/mpc/walking_mpc_16.hpp define no member of the classes it declares extern
# (their destructors, implicitly defined where used, aside): those come from
# walkgen::walking_mpc_16, so these translation units did not compile them (docs/walking.md,
# "Compile time"). A member defined in its class body is implicitly inline, and GCC compiles it
# despite `extern template`: keep the heavy ones outside the class.
#   cmake -DNM=<nm> -DOBJECTS=<object|object|...> -P tests/mpc/check_extern_instantiation.cmake
foreach(_var NM OBJECTS)
  if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "check_extern_instantiation.cmake: -D${_var}=... is required")
  endif()
endforeach()
set(_classes "walkgen::WalkingMpc<double, 16, 4, 5>" "walkgen::WalkingModel<double, 16, 4, 5>"
             "walkgen::DenseQp<double, -1, -1>")
string(REPLACE "|" ";" _objects "${OBJECTS}")
set(_offenders "")
foreach(_object IN LISTS _objects)
  execute_process(COMMAND "${NM}" -C --defined-only "${_object}"
                  RESULT_VARIABLE _rc OUTPUT_VARIABLE _symbols ERROR_VARIABLE _error)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "walking_mpc_16_extern: ${NM} failed on ${_object}: ${_error}")
  endif()
  string(REPLACE ";" "," _symbols "${_symbols}")
  string(REPLACE "\n" ";" _symbols "${_symbols}")
  foreach(_symbol IN LISTS _symbols)
    foreach(_class IN LISTS _classes)
      string(FIND "${_symbol}" "${_class}::" _pos)
      string(FIND "${_symbol}" "${_class}::~" _destructor)
      if(NOT _pos EQUAL -1 AND _destructor EQUAL -1)
        list(APPEND _offenders "${_object}: ${_symbol}")
      endif()
    endforeach()
  endforeach()
endforeach()
if(_offenders)
  string(REPLACE ";" "\n  " _lines "${_offenders}")
  message(FATAL_ERROR "walking_mpc_16_extern: compiled despite the extern header:\n  ${_lines}")
endif()
list(LENGTH _objects _count)
message(STATUS "walking_mpc_16_extern: ${_count} object files define no precompiled member")
