# Runs `collide2d toi` on bad query files: each must exit 2 with one line on
# stderr naming the file, the line and the field, and print no CSV.
function(expect_bad file line field)
  execute_process(COMMAND ${EXE} toi ${DATA}/${file} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "${file}: expected exit 2, got ${rc}\nstdout: ${out}\nstderr: ${err}")
  endif()
  if(NOT out STREQUAL "")
    message(FATAL_ERROR "${file}: a rejected file must print no CSV, got: ${out}")
  endif()
  string(FIND "${err}" "${file}: line ${line}: ${field}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${file}: stderr should name 'line ${line}: ${field}', got: ${err}")
  endif()
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "${file}: expected exactly one line on stderr, got: ${err}")
  endif()
endfunction()

expect_bad(not_json.jsonl 2 "not valid JSON")
expect_bad(non_finite.jsonl 3 "balls[0].position[1]: must be a finite number")
expect_bad(negative_radius.jsonl 2 "balls[0].radius: must be > 0")
expect_bad(unknown_field.jsonl 2 "balls[0].raduis: unknown field")
expect_bad(overlap_wall.jsonl 2 "balls[0]: overlaps walls[0] at t = 0")
expect_bad(overlap_balls.jsonl 1 "balls[1]: overlaps balls[0] at t = 0")
expect_bad(missing_horizon.jsonl 1 "horizon: missing")
# Squares of 3e9 do not fit the fixed format (±9.2e18): reported, never wrapped.
expect_bad(fixed_overflow.jsonl 2 "fixed-point overflow" --mode fixed)
# A relative acceleration of 1e160 squares beyond the double range (1e308):
# reported, never answered with a NaN time (a speed of 1e199 gave "0,1,-nan";
# fuzz_toi_query found it; such a speed is now refused when the line is read,
# its kinetic energy overflowing).
expect_bad(strict_overflow.jsonl 2 "strict-mode overflow")

# A good file: blank lines skipped, extra top-level keys ignored (SPEC.md),
# answers in input order with 17 significant digits.
execute_process(COMMAND ${EXE} toi ${DATA}/good.jsonl RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(expected "index,hit,t\n0,1,1.5\n1,1,1.5\n2,0,\n")
if(NOT rc EQUAL 0 OR NOT out STREQUAL expected)
  message(FATAL_ERROR "good.jsonl: expected exit 0 and\n${expected}got ${rc}:\n${out}${err}")
endif()
# Usage errors are exit 2 as well.
execute_process(COMMAND ${EXE} toi ${DATA}/good.jsonl --method nonsense RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "an unknown --method must exit 2, got ${rc}")
endif()
execute_process(COMMAND ${EXE} toi ${DATA}/does_not_exist.jsonl RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "a missing file must exit 2, got ${rc}")
endif()
