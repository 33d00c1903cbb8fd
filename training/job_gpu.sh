#!/usr/bin/env bash
# A job longer than one command on the NVIDIA machine, run so that a machine given back between two
# commands (after 30 s idle, with its /tmp) costs only the step in flight:
#   training/job_gpu.sh start SCRIPT [MARKER]   starts SCRIPT as a job that outlives the command
#                                              (setsid; its output in /tmp/job.log), then waits
#   training/job_gpu.sh wait [MARKER]           waits for a job a previous command started
# Either waits until /tmp/job.log holds MARKER (default JOB-END) or WAIT_S seconds (default 560)
# have passed, then copies everything the job has put in /tmp/out so far to $OUT: the weights of a
# finished training come back even while its evaluation still runs. More files than the 8 a command
# returns come back as one $OUT/out.tgz instead. `wait` on a fresh machine (no
# /tmp/job.log: the previous one was given back, the job with it) says so and exits 3 at once,
# rather than spending the command's device time waiting for a log that cannot come. Exits 0 when
# the marker came, 2 when the wait ran out first.
set -u
usage="usage: training/job_gpu.sh start SCRIPT [MARKER] | wait [MARKER]"
log=/tmp/job.log
case "${1:-}" in
  start)
    script=${2:?$usage}
    marker=${3:-JOB-END}
    mkdir -p /tmp/out
    (setsid nohup bash "$script" > "$log" 2>&1 < /dev/null &)
    ;;
  wait)
    marker=${2:-JOB-END}
    if [ ! -f "$log" ]; then
      echo "no $log: this is a fresh machine, the job and its /tmp went with the last one" >&2
      exit 3
    fi
    ;;
  *)
    echo "$usage" >&2
    exit 2
    ;;
esac
deadline=$(($(date +%s) + ${WAIT_S:-560}))
status=2
while true; do
  if grep -q "$marker" "$log" 2>/dev/null; then
    status=0
    break
  fi
  if [ "$(date +%s)" -ge "$deadline" ]; then
    break
  fi
  sleep 5
done
tail -n 20 "$log"
if [ -n "${OUT:-}" ] && [ -d /tmp/out ]; then
  if [ "$(find /tmp/out -type f | wc -l)" -le 8 ]; then
    cp -r /tmp/out/. "$OUT/"
  else
    tar czf "$OUT/out.tgz" -C /tmp/out .
  fi
fi
exit $status
