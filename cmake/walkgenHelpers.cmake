# Helpers for walkgen's own tests, benchmarks and examples (never used by consumers).
#
#   walkgen_add_test(NAME <name> SOURCES <files...> [LIBS <libs...>] [LABELS <labels...>]
#                    [NO_PRECOMPILED])
#   walkgen_add_benchmark(NAME <name> SOURCES <files...> [LIBS <libs...>])
#   walkgen_add_example(NAME <name> SOURCES <files...> [LIBS <libs...>] [ARGS <args...>]
#                       [CASES <cases...>])
#   walkgen_add_compile_fail_test(NAME <name> SOURCE <file> REGEX <regex>)
#
# Relative SOURCES are relative to the calling CMakeLists.txt. Every target gets our warning flags
# (never the INTERFACE library itself). Tests can include "support/..." (test helpers) from tests/;
# examples and benchmarks cannot: what they share with tests is in the library (include/walkgen/).
#
# Tests and examples compile the heavy templates (WalkingMpc<double, 16>, the closed loop) once,
# in libraries they link (CMakeLists.txt, "The project's programs compile the heavy templates
# once"); NO_PRECOMPILED keeps a test header-only, e.g. one that compiles walkgen with flags of
# its own. Benchmarks always compile walkgen header-only, as a user does.
include_guard(GLOBAL)

set(_walkgen_helpers_dir "${CMAKE_CURRENT_LIST_DIR}")

# Warnings for our own targets only. -Wconversion/-Wshadow are too noisy inside Eigen.
function(walkgen_target_warnings target)
  if(MSVC)
    target_compile_options(${target} PRIVATE /W4 /permissive-)
  else()
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Werror=return-type)
  endif()
endfunction()

function(_walkgen_check_args fn)
  if(NOT _arg_NAME)
    message(FATAL_ERROR "${fn}: NAME is required")
  endif()
  if(_arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${fn}(${_arg_NAME}): unknown arguments: ${_arg_UNPARSED_ARGUMENTS}")
  endif()
endfunction()

# A GoogleTest executable; each TEST() becomes one ctest through gtest_discover_tests.
# Default label: "unit".
function(walkgen_add_test)
  cmake_parse_arguments(_arg "NO_PRECOMPILED" "NAME;FIXTURES_REQUIRED" "SOURCES;LIBS;LABELS"
                        ${ARGN})
  _walkgen_check_args(walkgen_add_test)
  if(NOT _arg_SOURCES)
    message(FATAL_ERROR "walkgen_add_test(${_arg_NAME}): SOURCES is required")
  endif()
  if(NOT _arg_LABELS)
    set(_arg_LABELS unit)
  endif()
  if(NOT TARGET GTest::gtest_main AND NOT TARGET GTest::Main)
    find_package(GTest REQUIRED)
  endif()
  include(GoogleTest)
  set(_gtest_main GTest::gtest_main)
  if(NOT TARGET GTest::gtest_main)  # FindGTest of CMake < 3.20 only defines GTest::Main
    set(_gtest_main GTest::Main)
  endif()

  add_executable(${_arg_NAME} ${_arg_SOURCES})
  target_link_libraries(${_arg_NAME} PRIVATE walkgen::walkgen ${_gtest_main} ${_arg_LIBS})
  if(TARGET GTest::gmock)  # matchers in tests/support may use gmock
    target_link_libraries(${_arg_NAME} PRIVATE GTest::gmock)
  endif()
  target_include_directories(${_arg_NAME} PRIVATE "${PROJECT_SOURCE_DIR}/tests")
  target_compile_definitions(${_arg_NAME} PRIVATE WALKGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  walkgen_target_warnings(${_arg_NAME})
  if(NOT _arg_NO_PRECOMPILED)
    set_property(GLOBAL APPEND PROPERTY WALKGEN_PRECOMPILED_CONSUMERS ${_arg_NAME})
  endif()

  # ctest names are "<executable>.<Suite>.<Test>", unique across executables.
  gtest_discover_tests(${_arg_NAME}
    TEST_PREFIX "${_arg_NAME}."
    TEST_LIST ${_arg_NAME}_TESTS
    DISCOVERY_TIMEOUT 60)

  # Labels are set by a ctest include file that runs after discovery: gtest_discover_tests'
  # PROPERTIES flattens a list value, so "LABELS a;b" would not survive it.
  set(_labels_file "${CMAKE_CURRENT_BINARY_DIR}/${_arg_NAME}_labels.cmake")
  file(WRITE "${_labels_file}"
       "if(${_arg_NAME}_TESTS)\n"
       "  set_tests_properties(\${${_arg_NAME}_TESTS} PROPERTIES LABELS \"${_arg_LABELS}\")\n")
  if(_arg_FIXTURES_REQUIRED)  # e.g. a model that an example test trains first
    file(APPEND "${_labels_file}"
         "  set_tests_properties(\${${_arg_NAME}_TESTS} PROPERTIES FIXTURES_REQUIRED "
         "\"${_arg_FIXTURES_REQUIRED}\")\n")
  endif()
  file(APPEND "${_labels_file}" "endif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${_labels_file}")
endfunction()

# Benchmarks measure walkgen as a performance-minded user compiles it. walkgen is header-only,
# so the consumer's flags decide its speed; with this ON our benchmarks are built for the CPU
# they run on (WALKGEN_BENCHMARK_NATIVE_FLAGS). The `bench` preset turns it on; the `release`
# preset keeps the portable x86-64 baseline, and docs quote both.
option(WALKGEN_BENCHMARK_NATIVE "Compile walkgen's benchmarks for this CPU" OFF)
# -march=native (AVX2/FMA where present) without AVX-512: Eigen's 512-bit packets are slower
# on walking QPs (vectors of a few dozen entries) than its 256-bit ones — on the Xeon of
# docs/walking.md's tables, BM_TickStraight<16> takes 28.1 µs with them and 25.2 µs without
# (<64>: 425 and 444 µs). A cache variable, so a user can measure their own choice.
set(WALKGEN_BENCHMARK_NATIVE_FLAGS "-march=native;-mno-avx512f" CACHE STRING
  "Compile options of the benchmarks when WALKGEN_BENCHMARK_NATIVE is ON (a CMake list)")

# A Google Benchmark executable (run it by hand for numbers) plus one quick ctest
# "<name>_smoke" (label "benchmark") that runs every benchmark once, briefly.
function(walkgen_add_benchmark)
  cmake_parse_arguments(_arg "" "NAME" "SOURCES;LIBS" ${ARGN})
  _walkgen_check_args(walkgen_add_benchmark)
  if(NOT _arg_SOURCES)
    message(FATAL_ERROR "walkgen_add_benchmark(${_arg_NAME}): SOURCES is required")
  endif()
  find_package(benchmark REQUIRED)  # also sets benchmark_VERSION in this scope

  add_executable(${_arg_NAME} ${_arg_SOURCES})
  target_link_libraries(${_arg_NAME}
    PRIVATE walkgen::walkgen benchmark::benchmark benchmark::benchmark_main ${_arg_LIBS})
  target_compile_definitions(${_arg_NAME} PRIVATE WALKGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  walkgen_target_warnings(${_arg_NAME})
  if(WALKGEN_BENCHMARK_NATIVE AND NOT MSVC)
    target_compile_options(${_arg_NAME} PRIVATE ${WALKGEN_BENCHMARK_NATIVE_FLAGS})
  endif()

  # Google Benchmark < 1.8 parses --benchmark_min_time as plain seconds; 1.8 wants a unit suffix.
  set(_min_time 0.01)
  if(DEFINED benchmark_VERSION AND benchmark_VERSION VERSION_GREATER_EQUAL 1.8)
    set(_min_time 0.01s)
  endif()
  add_test(NAME ${_arg_NAME}_smoke
           COMMAND ${_arg_NAME} --benchmark_min_time=${_min_time} --benchmark_filter=.)
  set_tests_properties(${_arg_NAME}_smoke PROPERTIES LABELS benchmark TIMEOUT 300)
endfunction()

# An example program plus a ctest "example_<name>" (label "example") that runs it with ARGS in
# ${CMAKE_BINARY_DIR}/example_output, where its CSV/PNG files land. With CASES, one ctest
# "example_<name>_<case>" per case instead, running `<name> <case> ARGS...`.
function(walkgen_add_example)
  cmake_parse_arguments(_arg "" "NAME" "SOURCES;LIBS;ARGS;CASES" ${ARGN})
  _walkgen_check_args(walkgen_add_example)
  if(NOT _arg_SOURCES)
    message(FATAL_ERROR "walkgen_add_example(${_arg_NAME}): SOURCES is required")
  endif()

  if(NOT TARGET CLI11::CLI11)
    find_package(CLI11 CONFIG QUIET)
    if(NOT CLI11_FOUND)
      message(FATAL_ERROR "walkgen: the examples parse their command lines with CLI11, which was "
                          "not found. Install the Debian package libcli11-dev (bash "
                          "scripts/setup.sh does), or configure with -DWALKGEN_BUILD_EXAMPLES=OFF.")
    endif()
  endif()
  add_executable(${_arg_NAME} ${_arg_SOURCES})
  target_link_libraries(${_arg_NAME} PRIVATE walkgen::walkgen CLI11::CLI11 ${_arg_LIBS})
  # "common/cli.hpp" (the command-line conventions) from examples/.
  target_include_directories(${_arg_NAME} PRIVATE "${PROJECT_SOURCE_DIR}/examples")
  target_compile_definitions(${_arg_NAME} PRIVATE WALKGEN_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  walkgen_target_warnings(${_arg_NAME})
  set_property(GLOBAL APPEND PROPERTY WALKGEN_EXAMPLE_TARGETS ${_arg_NAME})
  set_property(GLOBAL APPEND PROPERTY WALKGEN_PRECOMPILED_CONSUMERS ${_arg_NAME})

  set(_out "${CMAKE_BINARY_DIR}/example_output")
  file(MAKE_DIRECTORY "${_out}")
  if(NOT _arg_CASES)
    add_test(NAME example_${_arg_NAME} COMMAND ${_arg_NAME} ${_arg_ARGS} WORKING_DIRECTORY "${_out}")
    set_tests_properties(example_${_arg_NAME} PROPERTIES LABELS example TIMEOUT 300)
  endif()
  foreach(_case IN LISTS _arg_CASES)
    add_test(NAME example_${_arg_NAME}_${_case} COMMAND ${_arg_NAME} ${_case} ${_arg_ARGS}
             WORKING_DIRECTORY "${_out}")
    set_tests_properties(example_${_arg_NAME}_${_case} PROPERTIES LABELS example TIMEOUT 300)
  endforeach()
endfunction()

# The ctest "examples_help" (label "example"): every program added by walkgen_add_example so far
# answers --help with exit 0 and a usage text ("Usage:", "Options:"), and rejects an unknown
# option with a non-zero exit and one line on stderr (tests/examples_help.cmake). Call it once,
# after the last walkgen_add_example.
function(walkgen_add_examples_help_test)
  get_property(_targets GLOBAL PROPERTY WALKGEN_EXAMPLE_TARGETS)
  set(_files "")
  foreach(_target IN LISTS _targets)
    list(APPEND _files "$<TARGET_FILE:${_target}>")
  endforeach()
  string(REPLACE ";" "|" _files "${_files}")
  add_test(NAME examples_help
           COMMAND "${CMAKE_COMMAND}" "-DPROGRAMS=${_files}"
                   -P "${PROJECT_SOURCE_DIR}/tests/examples_help.cmake")
  set_tests_properties(examples_help PROPERTIES LABELS example TIMEOUT 120)
endfunction()

# A ctest that passes only if compiling SOURCE fails AND the compiler output matches REGEX
# (e.g. a static_assert's "walkgen: ..." sentence). The object library <name> is excluded from
# the normal build; the test builds it on its own with `cmake --build`.
function(walkgen_add_compile_fail_test)
  cmake_parse_arguments(_arg "" "NAME;SOURCE;REGEX" "" ${ARGN})
  _walkgen_check_args(walkgen_add_compile_fail_test)
  if(NOT _arg_SOURCE OR NOT _arg_REGEX)
    message(FATAL_ERROR "walkgen_add_compile_fail_test(${_arg_NAME}): SOURCE and REGEX are required")
  endif()

  add_library(${_arg_NAME} OBJECT "${_arg_SOURCE}")
  target_link_libraries(${_arg_NAME} PRIVATE walkgen::walkgen)
  target_include_directories(${_arg_NAME} PRIVATE "${PROJECT_SOURCE_DIR}/tests")
  set_target_properties(${_arg_NAME} PROPERTIES EXCLUDE_FROM_ALL TRUE
                                                EXCLUDE_FROM_DEFAULT_BUILD TRUE)
  walkgen_target_warnings(${_arg_NAME})

  add_test(NAME ${_arg_NAME}
           COMMAND "${CMAKE_COMMAND}"
                   "-DBUILD_DIR=${CMAKE_BINARY_DIR}"
                   "-DTARGET=${_arg_NAME}"
                   "-DCONFIG=$<CONFIG>"
                   "-DREGEX=${_arg_REGEX}"
                   -P "${_walkgen_helpers_dir}/run_compile_fail.cmake")
  # Two builds in one build tree at once would fight over the generator's state files.
  set_tests_properties(${_arg_NAME} PROPERTIES
    LABELS compile_fail TIMEOUT 300 RESOURCE_LOCK walkgen_build_tree)
endfunction()

# Links every test and example registered in WALKGEN_PRECOMPILED_CONSUMERS to the instantiations
# compiled once (CMakeLists.txt, "The project's programs compile the heavy templates once"):
# those that link walkgen::simulation (directly or through walkgen::navigation) to the closed
# loop (src/simulation_loop_16.hpp), the others to WalkingMpc<double, 16>
# (walkgen/mpc/walking_mpc_16.hpp). The header is force-included, so the sources stay as a user
# writes them. Call it once, after the last test and example.
function(walkgen_link_precompiled)
  get_property(_targets GLOBAL PROPERTY WALKGEN_PRECOMPILED_CONSUMERS)
  foreach(_target IN LISTS _targets)
    get_target_property(_libs ${_target} LINK_LIBRARIES)
    if(TARGET walkgen_simulation_loop_16 AND
       ("walkgen::simulation" IN_LIST _libs OR "walkgen::navigation" IN_LIST _libs))
      set(_library walkgen_simulation_loop_16)
      set(_header "${PROJECT_SOURCE_DIR}/src/simulation_loop_16.hpp")
    else()
      set(_library walkgen::walking_mpc_16)
      set(_header "${PROJECT_SOURCE_DIR}/include/walkgen/mpc/walking_mpc_16.hpp")
    endif()
    target_link_libraries(${_target} PRIVATE ${_library})
    if(MSVC)
      target_compile_options(${_target} PRIVATE "/FI${_header}")
    else()
      target_compile_options(${_target} PRIVATE "SHELL:-include \"${_header}\"")
    endif()
  endforeach()
endfunction()
