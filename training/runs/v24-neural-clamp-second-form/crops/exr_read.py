"""A minimal reader of the scanline EXR files Lucid writes (uncompressed, ZIPS or ZIP; half or float
channels), for machines whose Python has no EXR module."""
import struct, zlib
import numpy as np

def read_exr(path):
    """RGB float32 of a scanline EXR (no/ZIPS/ZIP compression, half or float channels)."""
    data = open(path, 'rb').read()
    assert struct.unpack_from('<I', data, 0)[0] == 20000630
    pos = 8
    header = {}
    while data[pos] != 0:
        end = data.index(b'\0', pos); name = data[pos:end].decode(); pos = end + 1
        end = data.index(b'\0', pos); typ = data[pos:end].decode(); pos = end + 1
        size = struct.unpack_from('<i', data, pos)[0]; pos += 4
        header[name] = (typ, data[pos:pos + size]); pos += size
    pos += 1
    ch = header['channels'][1]; chans = []; p = 0
    while ch[p] != 0:
        end = ch.index(b'\0', p); nm = ch[p:end].decode(); p = end + 1
        pt = struct.unpack_from('<i', ch, p)[0]; p += 16
        chans.append((nm, pt))
    xmin, ymin, xmax, ymax = struct.unpack('<4i', header['dataWindow'][1])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    comp = header['compression'][1][0]
    lines = {0: 1, 2: 1, 3: 16}[comp]
    nblocks = (h + lines - 1) // lines
    offsets = struct.unpack_from(f'<{nblocks}Q', data, pos)
    out = {nm: np.zeros((h, w), np.float32) for nm, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from('<ii', data, off)
        raw = data[off + 8: off + 8 + size]
        n = min(lines, ymax + 1 - y)
        expected = sum(w * n * (2 if pt == 1 else 4) for _, pt in chans)
        if comp != 0 and size < expected:
            t = np.frombuffer(zlib.decompress(raw), np.uint8).astype(np.int32)
            t = np.cumsum(np.concatenate([t[:1], t[1:] - 128])) % 256
            t = t.astype(np.uint8)
            half = (len(t) + 1) // 2
            b = np.empty_like(t); b[0::2] = t[:half]; b[1::2] = t[half:]
            raw = b.tobytes()
        q = 0
        for yy in range(n):
            for nm, pt in chans:
                nbytes = w * (2 if pt == 1 else 4)
                arr = np.frombuffer(raw[q:q + nbytes], np.float16 if pt == 1 else np.float32)
                out[nm][y - ymin + yy] = arr; q += nbytes
    return np.stack([out['R'], out['G'], out['B']], -1)
