# Runs the driver on a scene into a fresh folder and checks its log: MATCH must be in it and
# NOT_MATCH must not.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${UPGRAIN} --output ${WORK}/out ${PRM} RESULT_VARIABLE code OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "upgrain failed:\n${out}\n${err}")
endif()
if(NOT out MATCHES "${MATCH}")
  message(FATAL_ERROR "the log does not say '${MATCH}':\n${out}")
endif()
if(out MATCHES "${NOT_MATCH}")
  message(FATAL_ERROR "the log says '${NOT_MATCH}':\n${out}")
endif()
message(STATUS "${out}")
