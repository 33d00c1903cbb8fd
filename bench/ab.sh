# A/B of several lucid binaries, back to back: pass medians (ms) at 1920x1080 (SCENES, ALGO override).
set -e
for s in ${SCENES:-cornell-box classroom cornell-teapot covered-light blinds-room caustics}; do
  for b in "$@"; do
    .gpu/$b bench --scene $s --algo ${ALGO:-pt} --size 1920x1080 --spp 1 --max-depth 8 --frames 100 --warmup 10 --json /tmp/r.json > /dev/null
    python3 -c "
import json
r = json.load(open('/tmp/r.json'))
print('$s', '$b', ' '.join('%s=%.3f' % (k, v['median']) for k, v in r['passes_ms'].items() if v['median'] > 0.05))"
  done
done
