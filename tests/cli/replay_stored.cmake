# `collide2d replay` of a run file written on x86-64 by a gcc -O3 build
# (datasets/determinism/run_x86_64_MODE.h5), on the machine under test: the
# re-simulation here must match the file bit for bit (every frame's doubles,
# state hash and, in fixed mode, raw Q63.64 words; every event). Under qemu
# this is the cross-architecture replay of issue 15. The stored file is
# copied first: replay only reads, but the dataset must stay untouched.
file(MAKE_DIRECTORY ${WORK_DIR})
set(copy ${WORK_DIR}/run_x86_64_${MODE}.h5)
file(COPY_FILE ${STORED} ${copy})
execute_process(COMMAND ${EXE} replay ${copy} RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "replay of ${STORED} failed (${rc}): ${stdout}${stderr}")
endif()
if(NOT stdout MATCHES "identical, ([0-9]+) frames and ([0-9]+) events, bit for bit")
  message(FATAL_ERROR "replay of ${STORED} did not say identical: ${stdout}")
endif()
# The file must have had something to compare.
if(CMAKE_MATCH_1 LESS 2 OR CMAKE_MATCH_2 LESS 1)
  message(FATAL_ERROR "replay of ${STORED} compared too little: ${stdout}")
endif()
message(STATUS "${stdout}")
