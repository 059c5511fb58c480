# cmake -DJAUSD=... -DCONFIG=... -DRC=<exit code> -DPATTERN=<regex> -DARGS=<more> -P expect_jausd.cmake
# Runs `jausd --config CONFIG ARGS`; fails unless it exits RC and its output
# matches PATTERN. A refusal (RC 2) is one line on stderr.
execute_process(COMMAND ${JAUSD} --config ${CONFIG} ${ARGS}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 30)
set(all "${out}${err}")
if(NOT rc STREQUAL RC)
  message(FATAL_ERROR "jausd --config ${CONFIG} ${ARGS}: exit ${rc}, wanted ${RC}\n${all}")
endif()
if(NOT all MATCHES "${PATTERN}")
  message(FATAL_ERROR "jausd --config ${CONFIG} ${ARGS}: output does not match '${PATTERN}':\n${all}")
endif()
if(RC EQUAL 2 AND ARGS MATCHES "--check-config")
  string(STRIP "${err}" stripped)
  if(stripped MATCHES "\n")
    message(FATAL_ERROR "jausd --config ${CONFIG} ${ARGS}: more than one line:\n${err}")
  endif()
endif()
message(STATUS "jausd --config ${CONFIG} ${ARGS}: exit ${rc} as wanted: ${all}")
