#!/usr/bin/env bash
# Thirty-third session (one H200): SVGF's firefly clamp as the thirty-second session reshaped it (a
# bound on the sample at 32x the history around it; a second bright neighbour for new light),
# measured where the session that made it could not: the SVGF passes' time at 1920x1080 with the
# clamp on and off, and the held-out sequences with the defaults. Runs the thirty-first session's
# job (`../v21-svgf-firefly-clamp/job.sh`) without its edge-pass round.
# .gpu/lucid.xz: the release lucid binary of 52b0d2c.
set -u
mkdir -p /tmp/bin /tmp/out && xz -dc .gpu/lucid.xz > /tmp/bin/lucid && chmod +x /tmp/bin/lucid
rm -rf /tmp/repo && cp -r . /tmp/repo && cd /tmp/repo
echo "START $(date +%s)"
EDGE_EMISSION=0 LUCID=/tmp/bin/lucid training/runs/v21-svgf-firefly-clamp/job.sh /tmp/res/headroom32_1080p
echo "END $? $(date +%s)"
tar -C /tmp/res -czf /tmp/out/headroom32_1080p.tar.gz headroom32_1080p
echo JOB-END
