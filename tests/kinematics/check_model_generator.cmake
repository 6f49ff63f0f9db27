# ctest model_generator_reproduces, script mode:
#   cmake -DPYTHON=<python3> -DSOURCE_DIR=<repo root> -DOUTPUT_DIR=<scratch> -P this file
# Runs models/generate.py into OUTPUT_DIR and fails unless each generated file equals the
# committed one under models/ byte for byte: the URDF and the MJCF come from one description.
foreach(_var PYTHON SOURCE_DIR OUTPUT_DIR)
  if(NOT ${_var})
    message(FATAL_ERROR "check_model_generator: ${_var} is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUTPUT_DIR}")
execute_process(COMMAND "${PYTHON}" "${SOURCE_DIR}/models/generate.py" --output-dir "${OUTPUT_DIR}"
                RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "models/generate.py failed (exit ${_rc})")
endif()
foreach(_file walkgen_humanoid.urdf walkgen_humanoid.xml)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files
                          "${OUTPUT_DIR}/${_file}" "${SOURCE_DIR}/models/${_file}"
                  RESULT_VARIABLE _differs)
  if(_differs)
    message(FATAL_ERROR "models/${_file} differs from what models/generate.py writes "
                        "(${OUTPUT_DIR}/${_file}). Edit the generator, never the generated "
                        "files, and regenerate with: /usr/bin/python3 models/generate.py")
  endif()
  message(STATUS "models/${_file}: reproduced byte for byte")
endforeach()
