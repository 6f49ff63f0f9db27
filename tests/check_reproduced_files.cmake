# ctests model_generator_reproduces and g1_conversion_reproduces, script mode:
#   cmake -DPYTHON=<python3> -DSCRIPT=<generator.py> -DFILES_DIR=<committed files' folder>
#         -DFILES=<name,name,...> -DOUTPUT_DIR=<scratch> -P this file
# Runs SCRIPT --output-dir OUTPUT_DIR and fails unless each of FILES it writes equals the
# committed one in FILES_DIR byte for byte: generated files are never edited by hand.
foreach(_var PYTHON SCRIPT FILES_DIR FILES OUTPUT_DIR)
  if(NOT ${_var})
    message(FATAL_ERROR "check_reproduced_files: ${_var} is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUTPUT_DIR}")
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" --output-dir "${OUTPUT_DIR}"
                RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "${SCRIPT} failed (exit ${_rc})")
endif()
string(REPLACE "," ";" _files "${FILES}")
foreach(_file IN LISTS _files)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUTPUT_DIR}/${_file}"
                          "${FILES_DIR}/${_file}"
                  RESULT_VARIABLE _differs)
  if(_differs)
    message(FATAL_ERROR "${FILES_DIR}/${_file} differs from what ${SCRIPT} writes "
                        "(${OUTPUT_DIR}/${_file}). Edit the script, never the generated files, "
                        "and regenerate with: /usr/bin/python3 ${SCRIPT}")
  endif()
  message(STATUS "${FILES_DIR}/${_file}: reproduced byte for byte")
endforeach()
