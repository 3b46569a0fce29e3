#!/usr/bin/env bash
# Runs one libFuzzer harness for a bounded time and summarises it. Run by
# ctest as fuzz.<NAME> in the sanitizer tree (Testing/Fuzz/CMakeLists.txt).
# Usage: scripts/run-fuzzer.sh FUZZER SECONDS WORK_DIR INPUT_DIR...
#   WORK_DIR/corpus collects what the fuzzer finds (kept between runs);
#   the INPUT_DIRs (seeds, regressions) are read, never written.
# Exits non-zero when the fuzzer finds a crash, a leak, a timeout or an
# out-of-memory input; the input is left in WORK_DIR/artifacts and named.
set -uo pipefail
fuzzer="${1:?usage: run-fuzzer.sh FUZZER SECONDS WORK_DIR INPUT_DIR...}"
seconds="${2:?}"
work="${3:?}"
shift 3
# Symbolized stack traces in sanitizer reports (llvm-14, scripts/install-deps.sh).
if [ -z "${ASAN_SYMBOLIZER_PATH:-}" ] && [ -x /usr/lib/llvm-14/bin/llvm-symbolizer ]; then
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
fi
# The harnesses hand readers that take a path a scratch file per process
# (Testing/Fuzz/mrgi_fuzz.h): in memory, that is 40 times the executions.
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then
  export TMPDIR=/dev/shm
fi
name="$(basename "$fuzzer")"
mkdir -p "$work/corpus" "$work/artifacts"
log="$work/fuzz.log"
# -timeout: one input may take 10 s (ASan, a slow machine); -rss_limit_mb:
# an input that makes a reader allocate more than 2 GiB is a finding.
"$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$work/artifacts/" \
  "$work/corpus" "$@" > "$log" 2>&1
status=$?
# The log holds one line per new input; show the start, the end and the stats.
head -n 12 "$log"
echo "..."
tail -n 40 "$log"
done_line="$(grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -n 1)"
runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
rate="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")"
cov="$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$done_line")"
ft="$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$done_line")"
corpus="$(sed -n 's/.* corp: \([0-9]*\/[0-9]*[a-zA-Z]*\).*/\1/p' <<<"$done_line")"
echo "run-fuzzer: $name: ${runs:-?} executions in ${seconds} s (${rate:-?}/s), cov ${cov:-?}, ft ${ft:-?}, corpus ${corpus:-?}"
if [ "$status" -ne 0 ]; then
  found="$(ls -1 "$work/artifacts" 2>/dev/null | head -n 5 | tr '\n' ' ')"
  echo "run-fuzzer: $name FAILED (status $status); input(s) in $work/artifacts: ${found:-none}" >&2
  echo "run-fuzzer: fix the reader, then check the input in as Testing/Fuzz/Regressions/<NAME>/<what-it-is>" >&2
  exit 1
fi
