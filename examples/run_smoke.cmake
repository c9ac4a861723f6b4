# A CI smoke run of an example (docs/examples.md): the driver on each scene of PRMS (a list),
# each into WORK/<scene name>, then the example's figure script on those folders with --check,
# which exits non-zero when the pattern its README promises does not hold; EACH (optional) is a
# script run the same way on each folder alone. Optional: RANKS (with MPIEXEC and NP_FLAG) runs the
# driver on that many MPI ranks; PLOT_ARGS (a list) are more arguments for PLOT.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(launch)
if(DEFINED RANKS)
  set(launch ${MPIEXEC} ${NP_FLAG} ${RANKS})
endif()
set(folders)
foreach(prm ${PRMS})
  get_filename_component(name ${prm} NAME_WE)
  execute_process(COMMAND ${launch} ${UPGRAIN} ${prm} --output ${WORK}/${name} RESULT_VARIABLE code
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "upgrain ${prm} failed:\n${out}\n${err}")
  endif()
  list(APPEND folders ${WORK}/${name})
endforeach()
execute_process(COMMAND ${PYTHON} ${PLOT} ${folders} --out ${WORK}/figures --check ${PLOT_ARGS} RESULT_VARIABLE code
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${PLOT} --check failed:\n${out}\n${err}")
endif()
message(STATUS "${out}")
if(DEFINED EACH)
  foreach(folder ${folders})
    execute_process(COMMAND ${PYTHON} ${EACH} ${folder} --out ${folder}/figures --check RESULT_VARIABLE code
                    OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT code EQUAL 0)
      message(FATAL_ERROR "${EACH} ${folder} --check failed:\n${out}\n${err}")
    endif()
    message(STATUS "${out}")
  endforeach()
endif()
