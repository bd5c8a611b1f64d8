# The installed package as a user meets it (ctest: consumer.installed_package): installs this
# build into a fresh prefix, builds tests/consumer against it with find_package(pss) alone,
# and runs the consumer and the installed pss executable.
# With the Python module, imports the installed package pss and renders with it.
# -D BUILD_DIR, WORK_DIR, SOURCE_DIR, GENERATOR, CXX_COMPILER, CXX_FLAGS, BUILD_TYPE, CUDA_ROOT,
#    PYTHON (the interpreter, empty without the module), PYTHON_DIR (its install dir in the prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("${out}")
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(installed bin/pss include/pss/points/project_cloud.hpp lib/cmake/pss/pssConfig.cmake)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "not installed: ${installed}")
  endif()
endforeach()
set(cuda_root)
if(CUDA_ROOT)
  set(cuda_root -DCUDAToolkit_ROOT=${CUDA_ROOT})
endif()
# The consumer gets the compiler and flags of this build (the sanitizers' runtime, when the
# library was built with them), and nothing else of it.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_CXX_FLAGS=${CXX_FLAGS} ${cuda_root})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
run(${prefix}/bin/pss info ${SOURCE_DIR}/data/bun_zipper.ply)
if(PYTHON)
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYTHON_DIR} ${PYTHON} -c
      "import pss, numpy as np; p = pss.read_points('${SOURCE_DIR}/data/bun_zipper.ply')[0]; \
i = pss.render(p, size=(32, 32)); assert pss.__file__.startswith('${prefix}'), pss.__file__; \
assert i.shape == (32, 32, 3) and i.std() > 10; print('import pss from', pss.__file__)")
endif()
