#!/usr/bin/env bash
# Pack Mitsuba 3 + Dr.Jit (CPython 3.12, Linux x86_64 wheels) into one tarball
# that can be carried to an offline GPU machine and used via PYTHONPATH.
#
#   bench/mitsuba/pack.sh                 # -> bench/mitsuba/mitsuba-py312.tar.xz
#   MITSUBA_VERSION=3.7.1 bench/mitsuba/pack.sh
#
# Needs: network access to PyPI (pip), python3, tar, xz.
# Keeps only the variants cuda_ad_rgb and scalar_rgb (plugins are shared by
# all variants and are kept whole).  Also drops C++ headers / CMake / pkgconfig
# files, which are only needed to build against Mitsuba.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
MITSUBA_VERSION="${MITSUBA_VERSION:-3.9.1}"
PYVER="${PYVER:-3.12}"
OUT="${OUT:-$HERE/mitsuba-py${PYVER/./}.tar.xz}"
KEEP_VARIANTS=(cuda_ad_rgb scalar_rgb)
PY="${PYTHON:-python3}"

# manylinux_2_17 .. 2_35 covers all recent mitsuba/drjit wheels (3.9.x is 2_28).
PLATFORMS=(--platform manylinux_2_17_x86_64 --platform manylinux2014_x86_64
           --platform manylinux_2_27_x86_64 --platform manylinux_2_28_x86_64
           --platform manylinux_2_31_x86_64 --platform manylinux_2_35_x86_64)

TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$TMP/wheels" "$TMP/site"

dl() {
    "$PY" -m pip download --no-deps --only-binary=:all: \
        --python-version "$PYVER" --implementation cp "${PLATFORMS[@]}" \
        -d "$TMP/wheels" "$1"
}

echo "== downloading mitsuba==$MITSUBA_VERSION (cp${PYVER/./})"
dl "mitsuba==$MITSUBA_VERSION"
MI_WHL="$(ls "$TMP"/wheels/mitsuba-*.whl)"

# The drjit version mitsuba requires (exact pin, e.g. 'drjit==1.5.0').
DRJIT_REQ="$("$PY" - "$MI_WHL" <<'EOF'
import sys, zipfile, re
z = zipfile.ZipFile(sys.argv[1])
meta = next(n for n in z.namelist() if n.endswith('.dist-info/METADATA'))
for line in z.read(meta).decode().splitlines():
    m = re.match(r'Requires-Dist:\s*(drjit\s*[=<>!~][^;]*)', line)
    if m:
        print(m.group(1).replace(' ', ''))
        break
else:
    sys.exit('no drjit requirement found in ' + meta)
EOF
)"
echo "== downloading $DRJIT_REQ"
dl "$DRJIT_REQ"

echo "== unpacking"
for w in "$TMP"/wheels/*.whl; do
    "$PY" -m zipfile -e "$w" "$TMP/site"
done

echo "== pruning variants (keeping: ${KEEP_VARIANTS[*]})"
MI="$TMP/site/mitsuba"
for f in "$MI"/llvm_ad_*.so "$MI"/cuda_ad_*.so "$MI"/scalar_*.so; do
    [ -e "$f" ] || continue
    base="$(basename "$f")"; v="${base%%.*}"
    keep=0
    for k in "${KEEP_VARIANTS[@]}"; do [ "$v" = "$k" ] && keep=1; done
    if [ $keep = 0 ]; then echo "  rm $base"; rm -f "$f"; fi
done
for k in "${KEEP_VARIANTS[@]}"; do
    ls "$MI/$k".*.so >/dev/null || { echo "missing variant module $k" >&2; exit 1; }
done
rm -rf "$MI/include" "$MI/cmake" "$MI/pkgconfig" \
       "$TMP/site/drjit/include" "$TMP/site/drjit/cmake"
find "$TMP/site" -name __pycache__ -type d -prune -exec rm -rf {} +
# Make mitsuba.variants() report only what is present.
"$PY" - "$MI/config.py" "${KEEP_VARIANTS[@]}" <<'EOF'
import re, sys
path, keep = sys.argv[1], sys.argv[2:]
s = open(path).read()
s = re.sub(r'^MI_VARIANTS = .*$', 'MI_VARIANTS = %r' % keep, s, flags=re.M)
open(path, 'w').write(s)
EOF

echo "== packing $OUT"
du -sh "$TMP/site"
tar -C "$TMP/site" -cf - . | xz -9 -T0 > "$TMP/out.tar.xz"
mv "$TMP/out.tar.xz" "$OUT"
ls -l "$OUT"
echo "== done: $(du -h "$OUT" | cut -f1)  $OUT"
echo "   use:  mkdir -p /tmp/mitsuba && tar -xJf $(basename "$OUT") -C /tmp/mitsuba && export PYTHONPATH=/tmp/mitsuba"
