#!/usr/bin/env bash
# Here (build host), from the project root: a debugger for the NVIDIA machine, whose image has
# none:
#   bench/pack_gdb.sh
# writes .gpu/gdb.tar.xz (about 9 MB): Debian's gdb-minimal as `gdb`, and in `lib/` every library
# it links but glibc's (the machine's own glibc serves). There, unpacked in DIR, it runs as
# `LD_LIBRARY_PATH=DIR/lib DIR/gdb`; give the debugged program its own library path back with
# `-ex 'set exec-wrapper env LD_LIBRARY_PATH=...'`. `GDB=1 bench/tests_gpu.sh` does all this.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p .gpu
work=$(mktemp -d)
(cd "$work" && apt-get download gdb-minimal > /dev/null 2>&1) || {
  echo "could not download gdb-minimal (apt-get download gdb-minimal)" >&2
  exit 1
}
dpkg -x "$work"/gdb-minimal_*.deb "$work/root"
mkdir -p "$work/pack/lib"
cp "$work/root/usr/bin/gdb" "$work/pack/gdb"
ldd "$work/pack/gdb" | awk '/=> \// {print $3}' | while read -r lib; do
  case "${lib##*/}" in
    libc.so.* | libm.so.* | libpthread.so.* | libdl.so.* | librt.so.* | ld-linux*) ;;
    *) cp -L "$lib" "$work/pack/lib/" ;;
  esac
done
if ldd "$work/pack/gdb" | grep -q 'not found'; then
  echo "gdb links libraries this machine lacks:" >&2
  ldd "$work/pack/gdb" | grep 'not found' >&2
  exit 1
fi
tar -cf - -C "$work/pack" gdb lib | xz -T2 -c > .gpu/gdb.tar.xz
rm -rf "$work"
ls -l .gpu/gdb.tar.xz
