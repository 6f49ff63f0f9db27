# Finds libtorch for walkgen's learning adapter (walkgen::torch: PPO, thesis §4.2 and §11.2).
# Included by the top-level CMakeLists.txt. Debian 12 ships libtorch 1.13 in libtorch-dev
# (CPU only); its CMake package defines the imported target `torch`. Sets
#   WALKGEN_TORCH_FOUND     libtorch with the target `torch` was found
#   WALKGEN_TORCH_PYTHON    ON when /usr/bin/python3 can `import torch` (python3-torch): the
#                           tests then check that saved policies load in Python too
include_guard(GLOBAL)

set(WALKGEN_TORCH_FOUND OFF)
if(NOT DEFINED WALKGEN_WITH_TORCH OR WALKGEN_WITH_TORCH)
  find_package(Torch CONFIG QUIET)
  if(Torch_FOUND AND TARGET torch)
    set(WALKGEN_TORCH_FOUND ON)
  endif()
endif()

set(WALKGEN_TORCH_PYTHON OFF)
if(WALKGEN_TORCH_FOUND AND EXISTS /usr/bin/python3)
  execute_process(COMMAND /usr/bin/python3 -c "import torch" RESULT_VARIABLE _walkgen_no_torch_py
                  OUTPUT_QUIET ERROR_QUIET)
  if(_walkgen_no_torch_py EQUAL 0)
    set(WALKGEN_TORCH_PYTHON ON)
  endif()
endif()

# Data-parallel training (walkgen/torch/distributed.hpp) uses c10d's Gloo process group, whose
# symbols are in libtorch; its headers include Gloo's own, which Debian ships in libgloo-dev.
#   WALKGEN_TORCH_DISTRIBUTED   ON when libtorch and the Gloo headers were found
set(WALKGEN_TORCH_DISTRIBUTED OFF)
if(WALKGEN_TORCH_FOUND)
  find_path(WALKGEN_GLOO_INCLUDE_DIR gloo/algorithm.h)
  if(WALKGEN_GLOO_INCLUDE_DIR)
    set(WALKGEN_TORCH_DISTRIBUTED ON)
  endif()
endif()
