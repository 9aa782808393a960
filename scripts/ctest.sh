#!/usr/bin/env bash
# Runs a build's tests: scripts/ctest.sh BUILD [CTEST_ARGS...] (make test, make test-asan).
# ctest's progress (two lines per test) goes to BUILD/Testing/ctest-progress.log, not to the
# terminal: CI keeps only the first part of a long log, and the progress of 400 tests twice over
# pushed what mattered out of it. Printed here: a line every 50 tests, ctest's summary, and when a
# test fails, its whole output (from LastTest.log, at most its last 300 lines) and the failed tests
# run once more, alone, to tell a failure that repeats from one that does not. The exit status
# stays non-zero either way: a test that fails once is a failure.
set -uo pipefail
if [ $# -lt 1 ] || [ ! -d "$1" ]; then
  echo "usage: scripts/ctest.sh BUILD_DIR [CTEST_ARGS...] (BUILD_DIR: a configured build folder)" >&2
  exit 2
fi
build="$1"
shift
mkdir -p "$build/Testing"
progress="$build/Testing/ctest-progress.log"
echo "ctest: $build $* (progress in $progress)"
# Progress: every 50th finished test, each failure as it happens; the summary from "tests passed".
ctest --test-dir "$build" "$@" 2>&1 | tee "$progress" | awk '
  /^ *[0-9]+\/[0-9]+ Test +#/ {
    split($1, f, "/")
    if ($0 !~ /Passed/) print
    else if (f[1] % 50 == 0 || f[1] == f[2]) print
    next
  }
  /tests passed|tests failed out of|The following tests|^[ \t]+[0-9]+ - |Total Test time/ { print }'
status=${PIPESTATUS[0]}
if [ "$status" -eq 0 ]; then
  exit 0
fi
log="$build/Testing/Temporary/LastTest.log"
if [ -f "$log" ]; then
  echo "== output of the failed tests (from $log), each at most its last 300 lines:"
  awk '
    /^[0-9]+\/[0-9]+ Testing: / { n = 0; inblock = 1 }
    inblock { lines[n++] = $0 }
    inblock && /time elapsed: / {
      inblock = 0; failed = 1
      for (i = 0; i < n; ++i) if (lines[i] == "Test Passed.") failed = 0
      if (failed) {
        start = n > 300 ? n - 300 : 0
        for (i = start; i < n; ++i) print lines[i]
        print ""
      }
    }' "$log"
fi
echo "== the failed tests once more, alone:"
ctest --test-dir "$build" --rerun-failed --output-on-failure -j 1 || true
echo "== tests failed in $build (see above)"
exit 1
