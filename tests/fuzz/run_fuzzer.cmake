# Runs one libFuzzer target for RUNS inputs, starting from the seed folders (read only) and a
# working corpus of its own; fails on any crash, sanitizer report, leak, timeout or out-of-memory
# (the fuzzer exits non-zero and writes the input to WORK/crash-*).
if(NOT EXISTS "${FUZZER}")
  message(FATAL_ERROR "${FUZZER} is missing: the clang sub-build (tests/fuzz) did not build; "
                      "scripts/setup installs clang and libclang-rt-14-dev")
endif()
file(MAKE_DIRECTORY ${WORK}/corpus)
set(dict "")
if(EXISTS "${DICT}")
  set(dict -dict=${DICT})
endif()
# -timeout (per input, s) catches hangs. 60: the seed examples/materials/full.json offers the
# whole space, whose 1,443,840 variants loading enumerates against the rules; under coverage and
# ASan that took 13 s on an idle 2-core machine (0.1 s in a release build), and over 10 s under
# load failed the test.
execute_process(
  COMMAND ${FUZZER} -runs=${RUNS} -seed=1 -max_len=8192 -timeout=60 -rss_limit_mb=2048 -print_final_stats=1
          ${dict} -artifact_prefix=${WORK}/ ${WORK}/corpus ${SEEDS}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "stat::number_of_executed_units: *[0-9]+" executed "${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzzer failed (exit ${rc}); the input is in ${WORK}/:\n${err}")
endif()
message(STATUS "${executed}")
