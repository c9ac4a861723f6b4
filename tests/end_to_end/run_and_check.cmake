# Runs the driver on one scene (under LAUNCHER, e.g. "mpiexec -n 2", when given), then the
# CHECK script on its output folder; the scripts of EXTRA (optional) are called with the
# folder, RANKS and COUNT; ARGS (optional) are further options of the driver. A second run into the
# same folder must be refused.
separate_arguments(launcher UNIX_COMMAND "${LAUNCHER}")
separate_arguments(args UNIX_COMMAND "${ARGS}")
if(NOT RANKS)
  set(RANKS 1)
endif()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${launcher} ${UPGRAIN} ${args} ${PRM} --output ${WORK}/out RESULT_VARIABLE code
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "upgrain failed:\n${out}\n${err}")
endif()
# p4est, behind the strain mesh, logs every mesh operation unless silenced (coupling/app/quiet_p4est.h).
if(out MATCHES "p[48]est")
  message(FATAL_ERROR "the driver printed p4est's log:\n${out}")
endif()
execute_process(COMMAND ${PYTHON} ${CHECK} ${WORK}/out ${COUNT} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "output check failed:\n${out}\n${err}")
endif()
foreach(script ${EXTRA})
  execute_process(COMMAND ${PYTHON} ${script} ${WORK}/out ${RANKS} ${COUNT} RESULT_VARIABLE code OUTPUT_VARIABLE check
                  ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${script}:\n${check}\n${err}")
  endif()
  message(STATUS "${check}")
endforeach()
# A second run into the same folder is refused: nothing the first run wrote is lost.
execute_process(COMMAND ${launcher} ${UPGRAIN} ${args} ${PRM} --output ${WORK}/out RESULT_VARIABLE code
                ERROR_VARIABLE err)
if(code EQUAL 0 OR NOT err MATCHES "already holds results")
  message(FATAL_ERROR "a second run into a folder with results was not refused: ${err}")
endif()
message(STATUS "${out}")
