# One fuzz test (fuzz/CMakeLists.txt): FUZZER replays CORPUS and REGRESSIONS, then fuzzes for
# SECONDS with libFuzzer's seed SEED, writing what it finds to WORK (emptied first), and a crashing
# input to WORK/crash-*; a non-zero exit fails the test.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/corpus")
# Without -max_total_time (0 seconds: replay only) libFuzzer would fuzz forever: -runs=0 runs the
# given inputs and stops.
if(SECONDS GREATER 0)
  set(bound -max_total_time=${SECONDS})
else()
  set(bound -runs=0)
endif()
# -timeout: one input taking over 10 s is a hang; -rss_limit_mb: two fuzzers run side by side on
# the 24 GiB CI machine; -error_exitcode is libFuzzer's default (1), named for clarity.
execute_process(
  COMMAND "${FUZZER}" ${bound} -seed=${SEED} -timeout=10 -rss_limit_mb=4096 -error_exitcode=1
          -print_final_stats=1 -artifact_prefix=${WORK}/ "${WORK}/corpus" "${CORPUS}" "${REGRESSIONS}"
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  file(GLOB artifacts "${WORK}/crash-*" "${WORK}/leak-*" "${WORK}/timeout-*" "${WORK}/oom-*" "${WORK}/slow-unit-*")
  message(FATAL_ERROR "${FUZZER} failed (exit ${status}); its input: ${artifacts}")
endif()
