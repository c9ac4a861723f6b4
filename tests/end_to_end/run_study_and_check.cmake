# Runs a study with the driver (optionally under mpiexec) and checks its folder; SOURCE, when
# given, is where the continua's material must come from (check_study.py).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
separate_arguments(launcher UNIX_COMMAND "${LAUNCHER}")
execute_process(COMMAND ${launcher} ${UPGRAIN} ${PRM} --output ${WORK}/out RESULT_VARIABLE code OUTPUT_VARIABLE out
                        ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "upgrain failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${PYTHON} ${CHECK} ${WORK}/out ${SOURCE} RESULT_VARIABLE code OUTPUT_VARIABLE check ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "study check failed:\n${check}\n${err}\n--- driver output:\n${out}")
endif()
message(STATUS "${out}\n${check}")
