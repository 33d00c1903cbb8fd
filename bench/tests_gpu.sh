#!/usr/bin/env bash
# On the NVIDIA machine, from the project root: every test binary bench/pack_tests.sh packed
# (.gpu/tests.tar.xz, .gpu/layers.tar.xz), under the Khronos validation layer, JOBS (6) binaries at
# a time, each for at most TIMEOUT_S (300) seconds:
#   source .gpu/env.sh && bench/tests_gpu.sh OUT_DIR
# The machine has neither Xvfb nor glslc, so the binaries of SKIP (window sandbox_xvfb
# hot_reload) are not run and the tests whose names hold a word of SKIP_TESTS (windowed, the game
# loop's window) are skipped. With REPEAT (1) above 1, each binary runs up to that many times and
# stops at its first failure, for crashes that come now and then (NVIDIA's driver unloaded between
# contexts crashed `traversal_gpu` in 10 runs of 12, and in one of the suite's first two runs).
# With GDB=1 (and .gpu/gdb.tar.xz, bench/pack_gdb.sh), each binary runs under gdb instead, which
# prints every thread's backtrace when it crashes or, interrupted at TIMEOUT_S, when it hangs
# (`pipeline_statistics` hung once in the fiftieth session's run and not in 428 more).
# Writes OUT_DIR/summary.txt (a line a binary: its exit status, the runs it took, its time,
# libtest's result line) and OUT_DIR/logs.tgz (each binary's output, of its last run); exits 1
# when a binary failed.
set -euo pipefail
out=$(realpath "${1:?usage: bench/tests_gpu.sh OUT_DIR}")
mkdir -p "$out"
work=/tmp/lucid-gpu-tests
rm -rf "$work" && mkdir -p "$work/logs"
tar -xJf .gpu/tests.tar.xz -C "$work"
tar -xJf .gpu/layers.tar.xz -C "$work"
if [ -n "${GDB:-}" ]; then
  mkdir -p "$work/gdb" && tar -xJf .gpu/gdb.tar.xz -C "$work/gdb"
fi
# The tests read their fixtures, and run `lucid`, from the tree they were built in.
built_in=$(cat "$work/built_in")
[ -e "$built_in" ] || { mkdir -p "$(dirname "$built_in")"; ln -s "$PWD" "$built_in"; }
mkdir -p "$built_in/target/release"
cp "$work/lucid" "$built_in/target/release/lucid"
skip=" ${SKIP:-window sandbox_xvfb hot_reload} "
export SKIP_TESTS=${SKIP_TESTS:-windowed} TIMEOUT_S=${TIMEOUT_S:-300} REPEAT=${REPEAT:-1} GDB=${GDB:-} work
# Waits up to SECONDS for process PID to end; fails if it still runs: until_ended PID SECONDS.
until_ended() {
  local pid=$1 left=$2
  while kill -0 "$pid" 2> /dev/null; do
    [ "$left" -gt 0 ] || return 1
    sleep 1
    left=$((left - 1))
  done
}
# One run of a test binary, its output in LOG: exits as the binary did, 124 past TIMEOUT_S.
run_binary() {
  local log=$1
  shift
  if [ -z "$GDB" ]; then
    timeout "$TIMEOUT_S" "$@" > "$log" 2>&1
    return
  fi
  LD_LIBRARY_PATH="$work/gdb/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$work/gdb/gdb" -q -batch \
    -ex "set exec-wrapper env LD_LIBRARY_PATH=${LD_LIBRARY_PATH:-}" -ex 'set pagination off' \
    -ex run -ex 'thread apply all bt 40' --args "$@" > "$log" 2>&1 &
  local gdb=$! status
  if ! until_ended "$gdb" "$TIMEOUT_S"; then
    # The binary is gdb's child: interrupted, it stops and gdb prints the backtraces.
    pkill -INT -P "$gdb"
    until_ended "$gdb" 30 || { pkill -KILL -P "$gdb"; kill -KILL "$gdb"; }
    wait "$gdb"
    echo "interrupted after $TIMEOUT_S s" >> "$log"
    return 124
  fi
  wait "$gdb"
  if grep -q '^\[Inferior 1 (process [0-9]*) exited normally\]' "$log"; then
    return 0
  fi
  status=$(sed -n 's/^\[Inferior 1 (process [0-9]*) exited with code \([0-9]*\)\]$/\1/p' "$log")
  # gdb prints the code in octal; without one the binary died of a signal (then 1).
  return $((8#${status:-1}))
}
export -f until_ended run_binary
run_one() {
  local name=$1 start status=0 word skips=() run=0
  for word in $SKIP_TESTS; do skips+=(--skip "$word"); done
  start=$(date +%s)
  while [ "$status" -eq 0 ] && [ "$run" -lt "$REPEAT" ]; do
    run=$((run + 1))
    VK_LAYER_PATH="$work/layers" LUCID_VALIDATION=1 \
      run_binary "$work/logs/$name.log" "$work/tests/$name" "${skips[@]}" || status=$?
  done
  echo "$name rc=$status runs=$run $(($(date +%s) - start))s $(grep -h '^test result' "$work/logs/$name.log" | tr '\n' ' ')"
}
export -f run_one
for name in $(ls "$work/tests"); do
  [[ "$skip" == *" $name "* ]] || echo "$name"
done | xargs -P "${JOBS:-6}" -I{} bash -c 'run_one {}' | sort > "$out/summary.txt"
tar -czf "$out/logs.tgz" -C "$work" logs
grep -v ' rc=0 ' "$out/summary.txt" && exit 1
echo "all $(wc -l < "$out/summary.txt") test binaries passed"
