# SPDX-License-Identifier: MIT
# silkgen --batch end to end with the committed tiny model (tests/tools/silkgen_batch_checks.py):
# shards cover the list once with 1/1-identical outputs (also from Slurm's variables), each output
# equals a single run's and passes mesh_check.py; broken inputs fail alone, reruns skip,
# --overwrite; bad shards, stem collisions and list syntax; --parallel 3 against --parallel 1
# (identical outputs, report rows and exit status). The Dask local-cluster run is the
# pytest tests/python/test_batch_dask.py (ctest python_silk_mesh).
if(Python3_FOUND AND TARGET silkgen)
  foreach(mode shards resume options parallel)
    add_test(NAME silkgen_batch_${mode}
             COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tools/silkgen_batch_checks.py ${mode}
                     $<TARGET_FILE:silkgen> ${PROJECT_SOURCE_DIR} ${SILK_SHARED_DIR_ABS})
    set_tests_properties(silkgen_batch_${mode} PROPERTIES TIMEOUT 600)
  endforeach()
endif()
