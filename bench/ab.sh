# A/B of several lucid binaries, back to back: pass medians (ms) at 1920x1080 (SCENES, ALGO and
# DENOISE override) of the passes above MIN_MS (0.05 unless set), with the main pass's register
# count when the driver reports pipeline statistics.
# The lines also go to $OUT/ab.txt when OUT is set (the device returns only a command's last
# 12,000 characters of output).
set -eo pipefail
for s in ${SCENES:-cornell-box classroom cornell-teapot covered-light blinds-room caustics}; do
  for b in "$@"; do
    .gpu/$b bench --scene $s --algo ${ALGO:-pt} --denoise ${DENOISE:-none} --size 1920x1080 --spp 1 \
      --max-depth 8 --frames 100 --warmup 10 --pipeline-statistics --json /tmp/r.json > /dev/null 2>&1
    python3 -c "
import json
r = json.load(open('/tmp/r.json'))
regs = {k.split('/')[-1]: v.get('Register Count') for k, v in (r.get('pipelines') or {}).items()}
main = {k: v for k, v in regs.items() if k in ('path_trace', 'path_trace_surfaces', 'path_trace_in_workgroup', 'camera', 'light')}
print('$s', '$b', ' '.join('%s=%.3f' % (k, v['median']) for k, v in r['passes_ms'].items() if v['median'] > ${MIN_MS:-0.05}), main)"
  done
done | if [ -n "${OUT:-}" ]; then tee -a "$OUT/ab.txt"; else cat; fi
