# Runs the driver on one scene under mpiexec with each rank count of RANKS, then
# compare_rank_outputs.py on the folders (the first is the reference). COMPUTE_GRIDS and
# COMPUTE_GRID_STRAIN (optional) check each run's compute-grid stress and strain, CHECKS
# (optional) its own results; OPTIONS (optional, one string) go to the driver (--study NAME).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(folders "")
separate_arguments(options UNIX_COMMAND "${OPTIONS}")
foreach(k ${RANKS})
  execute_process(COMMAND ${MPIEXEC} ${NP_FLAG} ${k} ${UPGRAIN} ${options} --output ${WORK}/np${k} ${PRM}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "upgrain on ${k} ranks failed:\n${out}\n${err}")
  endif()
  list(APPEND folders ${WORK}/np${k})
  # Each run's own checks (optional): a script given the folder, the rank count and the
  # particle count.
  foreach(script ${COMPUTE_GRIDS} ${COMPUTE_GRID_STRAIN} ${CHECKS})
    execute_process(COMMAND ${PYTHON} ${script} ${WORK}/np${k} ${k} ${PARTICLES} RESULT_VARIABLE code
                    OUTPUT_VARIABLE check ERROR_VARIABLE err)
    if(NOT code EQUAL 0)
      message(FATAL_ERROR "${script} on ${k} ranks:\n${check}\n${err}")
    endif()
    message(STATUS "${k} ranks: ${check}")
  endforeach()
endforeach()
execute_process(COMMAND ${PYTHON} ${CHECK} --other-blocks ${folders} RESULT_VARIABLE code OUTPUT_VARIABLE check
                ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "outputs differ between rank counts:\n${check}\n${err}")
endif()
message(STATUS "${check}")
