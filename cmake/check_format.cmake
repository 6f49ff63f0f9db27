# clang-format check (docs/design.md convention 19), script mode:
#   cmake -DSOURCE_DIR=<repo root> [-DCLANG_FORMAT=<exe>] [-DFIX=ON] -P cmake/check_format.cmake
# Checks every *.hpp/*.cpp/*.h under include/ src/ tests/ benchmarks/ examples/ that git knows
# of (tracked, or untracked but not ignored); outside a git checkout it globs those folders instead.
# With FIX=ON it rewrites the files in place. A missing clang-format is an error, not a skip.
if(NOT SOURCE_DIR)
  get_filename_component(SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
endif()
set(_dirs include src tests benchmarks examples)
# C++ only: clang-format formats any file it is given as C++ (it once mangled a shell script).
set(_extensions "hpp|cpp|h")

# --- clang-format --------------------------------------------------------------------------------
if(NOT CLANG_FORMAT)
  find_program(CLANG_FORMAT
    NAMES clang-format clang-format-14 clang-format-15 clang-format-16 clang-format-17
          clang-format-18 clang-format-19)
endif()
if(NOT CLANG_FORMAT)
  message(FATAL_ERROR
    "format check: clang-format not found. Install it (bash scripts/setup.sh, or "
    "apt-get install clang-format) or pass -DCLANG_FORMAT=/path/to/clang-format.")
endif()
execute_process(COMMAND "${CLANG_FORMAT}" --version
                OUTPUT_VARIABLE _version OUTPUT_STRIP_TRAILING_WHITESPACE)
message(STATUS "format check: ${_version} (${CLANG_FORMAT})")

# --- Files ---------------------------------------------------------------------------------------
set(_files "")
find_program(_git git)
if(_git AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(
    COMMAND "${_git}" -C "${SOURCE_DIR}" ls-files --cached --others --exclude-standard -- ${_dirs}
    RESULT_VARIABLE _git_rc
    OUTPUT_VARIABLE _git_out
    ERROR_QUIET)
  if(_git_rc EQUAL 0)
    string(REPLACE "\n" ";" _candidates "${_git_out}")
    foreach(_f IN LISTS _candidates)
      # ls-files --cached still lists files deleted from the work tree.
      if(_f MATCHES "\\.(${_extensions})$" AND EXISTS "${SOURCE_DIR}/${_f}")
        list(APPEND _files "${_f}")
      endif()
    endforeach()
    list(REMOVE_DUPLICATES _files)
  else()
    set(_git "")  # e.g. "dubious ownership": fall back to globbing
  endif()
else()
  set(_git "")
endif()
if(NOT _git)
  foreach(_d IN LISTS _dirs)
    file(GLOB_RECURSE _found RELATIVE "${SOURCE_DIR}"
         "${SOURCE_DIR}/${_d}/*.hpp" "${SOURCE_DIR}/${_d}/*.cpp" "${SOURCE_DIR}/${_d}/*.h")
    list(APPEND _files ${_found})
  endforeach()
endif()
list(SORT _files)
list(LENGTH _files _count)
if(_count EQUAL 0)
  message(STATUS "format check: no files to check")
  return()
endif()

# --- Fix or check --------------------------------------------------------------------------------
if(FIX)
  execute_process(COMMAND "${CLANG_FORMAT}" -i --style=file ${_files}
                  WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "format: clang-format -i failed (exit ${_rc})")
  endif()
  message(STATUS "format: formatted ${_count} files")
  return()
endif()

set(_bad "")
foreach(_f IN LISTS _files)
  execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror --style=file "${_f}"
                  WORKING_DIRECTORY "${SOURCE_DIR}"
                  RESULT_VARIABLE _rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT _rc EQUAL 0)
    list(APPEND _bad "${_f}")
  endif()
endforeach()

if(_bad)
  list(LENGTH _bad _nbad)
  string(REPLACE ";" "\n  " _bad_lines "${_bad}")
  string(REPLACE ";" " " _bad_args "${_bad}")
  message(FATAL_ERROR
    "format check: ${_nbad} of ${_count} files are not clang-formatted:\n  ${_bad_lines}\n"
    "Fix them from the repository root with:\n"
    "  ${CLANG_FORMAT} -i ${_bad_args}\n"
    "(or: cmake --build <build dir> --target format)")
endif()
message(STATUS "format check: ${_count} files OK")
