#!/usr/bin/env bash
# PNGs without alpha are read through libpng alone (host/image/png_read.c, linked into the
# binary) unless VKRAYCAST_PNG_READER=oiio asks for OpenImageIO: both give the same floats,
# bit for bit, for every colour type and bit depth a PNG without alpha can have (every level
# of 8 and 16 bits, palettes, grey of 1, 2 and 4 bits, Adam7 interlacing, gAMA and sRGB
# chunks, which neither applies), each checked against the float EXR oiiotool makes of the
# file; PNGs with alpha and damaged ones go to OpenImageIO, whose refusal stays the same;
# textured scenes render the same image through either reader; and neither a compare of
# two PNGs nor a textured render loads OpenImageIO.
# Usage: test_png_reader.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"

# The files, written byte by byte: libpng's and OpenImageIO's writers make only some kinds.
python3 - "$work" <<'EOF'
import os, struct, sys, zlib
out = sys.argv[1]
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
def pack(values, depth):
    """One row's samples as bytes at `depth` bits each."""
    if depth == 16: return b''.join(struct.pack('>H', v) for v in values)
    if depth == 8: return bytes(values)
    bits = ''.join(format(v, '0%db' % depth) for v in values)
    bits += '0' * (-len(bits) % 8)
    return bytes(int(bits[i:i + 8], 2) for i in range(0, len(bits), 8))
ADAM7 = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]
def png(name, w, h, depth, ctype, pixel, plte=None, extra=b'', interlace=0):
    """pixel(x, y) -> the samples of one pixel."""
    ihdr = struct.pack('>IIBBBBB', w, h, depth, ctype, 0, 0, interlace)
    passes = ADAM7 if interlace else [(0, 0, 1, 1)]
    data = b''
    for x0, y0, dx, dy in passes:
        xs, ys = range(x0, w, dx), range(y0, h, dy)
        if not xs or not ys: continue
        for y in ys:
            data += b'\0' + pack([s for x in xs for s in pixel(x, y)], depth)
    f = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + extra
    if plte: f += chunk(b'PLTE', plte)
    f += chunk(b'IDAT', zlib.compress(data)) + chunk(b'IEND', b'')
    open(os.path.join(out, name + '.png'), 'wb').write(f)
rgb = lambda x, y: [(16 * y + x) % 256, 255 - (16 * y + x) % 256, (7 * (16 * y + x)) % 256]
png('rgb8', 16, 16, 8, 2, rgb)
png('gray8', 16, 16, 8, 0, lambda x, y: [16 * y + x])
png('rgb16', 256, 256, 16, 2, lambda x, y: [256 * y + x, 65535 - 256 * y - x, (4099 * (256 * y + x)) % 65536])
png('gray16', 256, 256, 16, 0, lambda x, y: [256 * y + x])
png('palette8', 16, 16, 8, 3, lambda x, y: [16 * y + x], plte=bytes(rgb(i % 16, i // 16)[c] for i in range(256) for c in range(3)))
png('palette2', 13, 7, 2, 3, lambda x, y: [(x + y) % 4], plte=bytes([0, 0, 0, 255, 0, 0, 0, 255, 0, 9, 99, 199]))
for d in (1, 2, 4):
    png('gray%d' % d, 19, 5, d, 0, lambda x, y, d=d: [(3 * x + y) % (1 << d)])
png('interlaced', 21, 13, 8, 2, lambda x, y: [(11 * x + 3 * y) % 256, (5 * x * y) % 256, (x + 17 * y) % 256], interlace=1)
png('interlaced_gray4', 21, 13, 4, 0, lambda x, y: [(x + 2 * y) % 16], interlace=1)
png('srgb_gama', 16, 16, 8, 2, rgb, extra=chunk(b'sRGB', b'\0') + chunk(b'gAMA', struct.pack('>I', 45455)))
png('gama_1', 16, 16, 8, 2, rgb, extra=chunk(b'gAMA', struct.pack('>I', 100000)))
# Alpha, and a tRNS chunk: OpenImageIO's (it associates alpha).
png('rgba8', 16, 16, 8, 6, lambda x, y: rgb(x, y) + [(5 * x + 9 * y) % 256])
png('trns', 16, 16, 8, 2, rgb, extra=b'', interlace=0)
f = open(os.path.join(out, 'trns.png'), 'rb').read()
i = f.index(b'IDAT') - 4
open(os.path.join(out, 'trns.png'), 'wb').write(f[:i] + chunk(b'tRNS', struct.pack('>HHH', 0, 255, 0)) + f[i:])
EOF

# `same NAME`: NAME.png read through either reader gives the floats of the EXR that oiiotool
# (OpenImageIO) makes of it: compare's answers identical, max_error 0 with the libpng reader.
same() {
  local name=$1 r why=ok
  oiiotool "$work/$name.png" -d float -o "$work/$name.exr" 2>"$work/err" || because "oiiotool: $(head -c 200 "$work/err")"
  for r in png oiio; do
    VKRAYCAST_PNG_READER=$r "$bin" compare "$work/$name.png" "$work/$name.exr" --json >"$work/$r.json" 2>"$work/$r.err"
    echo "exit $?" >>"$work/$r.json"
  done
  cmp -s "$work/png.json" "$work/oiio.json" || because "the readers differ: $(diff "$work/png.json" "$work/oiio.json" | head -4)"
  [[ $(json_num max_error "$work/png.json") == 0 ]] || because "max_error $(json_num max_error "$work/png.json"): $(head -c 200 "$work/png.err")"
  check "$name" "$why"
}
for n in rgb8 gray8 rgb16 gray16 palette8 palette2 gray1 gray2 gray4 interlaced interlaced_gray4 srgb_gama gama_1 \
  rgba8 trns; do
  same "$n"
done

# The PNGs the renderer writes and the example scenes' textures, likewise.
"$bin" render "$scenes/showcase.json" --width 40 --height 28 --quiet --encoding srgb -o "$work/render.png" ||
  echo "FAIL: render"
same render
for t in "$scenes"/textures/*.png; do
  cp "$t" "$work/texture_$(basename "$t")"
  same "texture_$(basename "$t" .png)"
done

# Textured scenes: the same image through either reader.
for s in earth teapot uv_convention; do
  why=ok
  for r in png oiio; do
    VKRAYCAST_PNG_READER=$r "$bin" render "$scenes/$s.json" --width 48 --height 32 --quiet -o "$work/$s.$r.exr" ||
      because "$r: render failed"
  done
  same_pixels "$work/$s.png.exr" "$work/$s.oiio.exr" || because "the images differ"
  check "$s renders the same" "$why"
done

# A damaged PNG: libpng gives up, OpenImageIO refuses it in its own words, as before.
head -c 300 "$work/rgb16.png" >"$work/cut.png"
why=ok
for r in png oiio; do
  VKRAYCAST_PNG_READER=$r "$bin" compare "$work/cut.png" "$work/rgb16.png" >/dev/null 2>"$work/$r.err"
  echo "exit $?" >>"$work/$r.err"
done
cmp -s "$work/png.err" "$work/oiio.err" || because "the refusals differ: $(diff "$work/png.err" "$work/oiio.err" | head -4)"
grep -q "exit 2" "$work/png.err" || because "$(cat "$work/png.err")"
check "a damaged PNG: OpenImageIO's refusal" "$why"

# What the reader is for: no OpenImageIO to compare two PNGs or to render a textured scene.
why=ok
n=$(loads_oiio "$bin" compare "$work/rgb8.png" "$work/render.png")
[[ $n == 0 ]] || because "compare of two PNGs loaded OpenImageIO ($n)"
n=$(loads_oiio "$bin" render "$scenes/earth.json" --width 8 --height 8 --quiet -o "$work/e.exr")
[[ $n == 0 ]] || because "a render of earth.json loaded OpenImageIO ($n)"
n=$(VKRAYCAST_PNG_READER=oiio loads_oiio "$bin" compare "$work/rgb8.png" "$work/render.png")
[[ $n -ge 1 ]] || because "VKRAYCAST_PNG_READER=oiio did not load OpenImageIO"
check "PNGs without alpha are read without OpenImageIO" "$why"
finish
