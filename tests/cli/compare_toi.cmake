# Determinism: `collide2d toi` must reproduce a stored answer file to the last
# printed digit (17 significant digits identify a double). The stored answers
# were written by gcc -O3; CI also runs this test from a clang -O0 build.
execute_process(COMMAND ${EXE} toi ${QUERIES} --mode ${MODE} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "collide2d toi failed (${rc}): ${err}")
endif()
file(READ ${EXPECTED} expected)
if(NOT out STREQUAL expected)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/toi_${MODE}_actual.csv "${out}")
  message(FATAL_ERROR "answers differ from ${EXPECTED}; actual written to ${CMAKE_CURRENT_BINARY_DIR}/toi_${MODE}_actual.csv")
endif()
