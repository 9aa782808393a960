#!/usr/bin/env bash
# Runs a build's tests: scripts/ctest.sh BUILD [CTEST_ARGS...] (make test, make test-asan).
# When a test fails, its whole output is printed again at the end of the log (CI keeps only the
# log's tail, where the progress lines of the other tests would hide it), and the failed tests
# run once more, alone, to tell a failure that repeats from one that does not. The exit status
# stays non-zero either way: a test that fails once is a failure.
set -uo pipefail
if [ $# -lt 1 ] || [ ! -d "$1" ]; then
  echo "usage: scripts/ctest.sh BUILD_DIR [CTEST_ARGS...] (BUILD_DIR: a configured build folder)" >&2
  exit 2
fi
build="$1"
shift
if ctest --test-dir "$build" --output-on-failure "$@"; then
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
