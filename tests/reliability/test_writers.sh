#!/usr/bin/env bash
# A writer's failure is never success, and a run's outputs are one transaction (issue 13,
# classes 1 and 2). Cases are generated, not listed: every image format the README names,
# each under file-size limits (ulimit -f) at one block, half and just under the size the
# file needs, on a full filesystem (a small tmpfs, where this user may mount one), and an
# AOV or statistics file that fails while its image would fit; two outputs, or an output
# and an input, naming one file by any spelling. Each case: exit status 2, a message
# naming the file, the previous image (and AOV file) byte for byte as they were, and no
# temporary left behind.
# Usage: test_writers.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
temps() { find "$1" -maxdepth 1 \( -name '.vkraycast-*' -o -name '*.tmp*' \) | head -3; }
# The CPU reference renders: its frames stream into the same writers (rc_output_band) band by
# band as the GPU's, and a process that needs no Vulkan instance and no shader compile makes
# this test's ~80 renders cost their output code, which is what it tests. One GPU case
# below runs the streamed GPU path into a failing writer. The image is large enough for the
# file-size limits to fall inside its file; one sample a pixel, as its colours do not matter.
render=(render "$scenes/showcase.json" --width 256 --height 192 --spp 1 --quiet --backend cpu)
small_cpu=(--width 16 --height 12 --quiet --backend cpu)
# Runs the render with `limit` (a shell prefix) into DIR/out.EXT over a kept file.
# expect_failure NAME DIR EXT LIMIT_CMD [extra render args...]
expect_failure() {
  local name=$1 dir=$2 ext=$3 limit=$4
  shift 4
  local why=ok
  bash -c "$limit; exec \"\$@\"" _ "$bin" "${render[@]}" -o "$dir/out.$ext" "$@" >"$work/out" 2>"$work/err"
  local got=$?
  [[ $got == 2 ]] || why="exit status $got, expected 2"
  grep -q "out\.\(${ext}\|exr\): cannot write" "$work/err" || why="$why; stderr: $(head -c 300 "$work/err")"
  cmp -s "$dir/out.$ext" "$work/keep.$ext" || why="$why; the existing image changed"
  [[ -z "$(temps "$dir")" ]] || why="$why; temporaries left: $(temps "$dir")"
  check "$name" "$why"
}

formats=(png jpg bmp ppm exr tif hdr)
for ext in "${formats[@]}"; do
  # The file this render writes, to size the limits; and a different one to keep.
  "$bin" "${render[@]}" -o "$work/full.$ext" || { check "$ext: reference render" "failed"; continue; }
  "$bin" render "$scenes/shadows.json" -o "$work/keep.$ext" "${small_cpu[@]}"
  size=$(stat -c %s "$work/full.$ext")
  blocks=$(((size + 1023) / 1024))
  for limit in 1 $((blocks / 2)) $((blocks - 1)); do
    ((limit >= 1)) || continue
    cp "$work/keep.$ext" "$work/out.$ext"
    expect_failure "$ext under ulimit -f $limit (needs $size bytes)" "$work" "$ext" "ulimit -f $limit"
  done
  # The same render with room to spare succeeds and equals the reference byte for byte
  # (the checking proxy changes nothing that is written).
  cp "$work/keep.$ext" "$work/out.$ext"
  bash -c "ulimit -f $((blocks + 64)); exec \"\$@\"" _ "$bin" "${render[@]}" -o "$work/out.$ext"
  check "$ext with room: written" "$([[ $? == 0 ]] && "$bin" compare "$work/out.$ext" "$work/full.$ext" --fail 0 >/dev/null && echo ok || echo 'failed or differs')"
done
# PNGs are written with the Sub filter on every row at zlib level 5 (image_io.cpp, for
# speed at the old size): read back from the file's own bytes, not from the code.
check "png: Sub filter on every row, zlib level 2-5" "$(python3 - "$work/full.png" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
at, idat, width, height = 8, b"", 0, 0
while at < len(data):
    n, kind = struct.unpack(">I4s", data[at:at + 8])
    body = data[at + 8:at + 8 + n]
    if kind == b"IHDR":
        width, height, depth, color = struct.unpack(">IIBB", body[:10])
        channels = {0: 1, 2: 3, 4: 2, 6: 4}[color]
    elif kind == b"IDAT":
        idat += body
    at += 12 + n
rows = zlib.decompress(idat)
stride = 1 + width * channels
filters = {rows[y * stride] for y in range(height)}
level = idat[1] >> 6  # FLEVEL of the zlib header: 1 for levels 2-5
print("ok" if len(rows) == stride * height and filters == {1} and level == 1 else f"filters {filters}, FLEVEL {level}")
PY
)"
# The GPU backend into the same failing writer: its bands stream out between dispatches.
cp "$work/keep.exr" "$work/out.exr"
expect_failure "exr under ulimit -f 1, GPU backend" "$work" exr "ulimit -f 1" --backend gpu

# A full filesystem: a tmpfs just large enough for the kept file, where one can be mounted
# (root here and in CI; elsewhere the ulimit cases above cover the same code path).
fs=$work/tmpfs
mkdir -p "$fs"
if [[ $(id -u) == 0 ]] && mount -t tmpfs -o size=64k tmpfs "$fs" 2>/dev/null; then
  for ext in "${formats[@]}"; do
    cp "$work/keep.$ext" "$fs/out.$ext" && cp "$work/keep.$ext" "$work/keep_fs.$ext"
    # Fill what is left, but for a few blocks.
    dd if=/dev/zero of="$fs/fill" bs=1k count=1000 2>/dev/null
    rm -f "$fs/fill"
    free=$(( $(stat -f -c '%a * %S' "$fs") ))
    fallocate -l $((free > 8192 ? free - 8192 : 0)) "$fs/fill" 2>/dev/null
    expect_failure "$ext on a full filesystem" "$fs" "$ext" "true"
    rm -f "$fs/fill" "$fs/out.$ext"
  done
  # The statistics fail (on the full filesystem) where the image fits: both old files stay.
  echo '{ "old": true }' >"$fs/stats.json" && cp "$fs/stats.json" "$work/keep_stats.json"
  cp "$work/keep.png" "$work/out.png"
  free=$(( $(stat -f -c '%a * %S' "$fs") ))
  fallocate -l "$free" "$fs/fill" 2>/dev/null
  "$bin" "${render[@]}" -o "$work/out.png" --stats-json "$fs/stats.json" 2>"$work/err"
  got=$? why=ok
  [[ $got == 2 ]] || why="exit status $got, expected 2"
  grep -q "stats.json: cannot write statistics" "$work/err" || why="$why; stderr: $(head -c 300 "$work/err")"
  cmp -s "$work/out.png" "$work/keep.png" || why="$why; the image changed"
  cmp -s "$fs/stats.json" "$work/keep_stats.json" || why="$why; the statistics changed"
  [[ -z "$(temps "$fs")$(temps "$work")" ]] || why="$why; temporaries left"
  check "statistics fail after their image: both kept" "$why"
  rm -f "$fs/fill"
  umount "$fs"
else
  echo "note: no tmpfs could be mounted (not root): the full-filesystem cases ran as ulimit cases only"
fi

# The AOV file fails where the image fits (a PNG of ~40 KB, an AOV EXR of ~1.5 MB): both
# old files stay, nothing is left.
"$bin" render "$scenes/shadows.json" -o "$work/keep_aov.exr" "${small_cpu[@]}"
cp "$work/keep.png" "$work/out.png" && cp "$work/keep_aov.exr" "$work/out.exr"
expect_failure "AOV file fails after its image: image kept" "$work" png "ulimit -f 200" --aov "$work/out.exr"
check "AOV file fails after its image: AOV kept" "$(cmp -s "$work/out.exr" "$work/keep_aov.exr" && echo ok || echo changed)"
# Two roles naming one file, by every spelling (the same name, ./, the folder by .., a
# link): refused before rendering, every file as it was.
cp "$scenes/shadows.json" "$work/scene.json" && cp "$work/keep_aov.exr" "$work/same.exr"
ln -sf same.exr "$work/link.exr"
spellings=("$work/same.exr" "$work/./same.exr" "$work/../$(basename "$work")/same.exr" "$work/link.exr")
same_case() { # name expected-path-in-message args...
  local name=$1
  shift
  cp "$work/same.exr" "$work/before.exr" && cp "$work/scene.json" "$work/before.json"
  "$bin" "$@" >/dev/null 2>"$work/err"
  local got=$? why=ok
  [[ $got == 2 ]] || why="exit status $got, expected 2"
  grep -q "name the same file" "$work/err" || why="$why; stderr: $(head -c 300 "$work/err")"
  cmp -s "$work/same.exr" "$work/before.exr" && cmp -s "$work/scene.json" "$work/before.json" || why="$why; a file changed"
  [[ -z "$(temps "$work")" ]] || why="$why; temporaries left"
  check "$name" "$why"
}
small=(--width 16 --height 12 --quiet)
for s in "${spellings[@]}"; do
  same_case "-o and --aov: $s" render "$work/scene.json" -o "$work/same.exr" --aov "$s" "${small[@]}"
  same_case "-o and --stats-json: $s" render "$work/scene.json" -o "$work/same.exr" --stats-json "$s" "${small[@]}"
  same_case "--aov and --stats-json: $s" render "$work/scene.json" -o "$work/o.png" --aov "$work/same.exr" \
    --stats-json "$s" "${small[@]}"
  same_case "compare --diff naming A: $s" compare "$work/same.exr" "$work/keep_aov.exr" --diff "$s"
  same_case "compare --diff naming B: $s" compare "$work/keep_aov.exr" "$work/same.exr" --diff "$s"
done
for role in -o --stats-json; do
  same_case "$role naming the scene" render "$work/scene.json" -o "$work/o.png" "$role" "$work/./scene.json" "${small[@]}"
done
# A valid name of 250 bytes (NAME_MAX is 255): the temporary's name must not grow with it.
long=$(printf 'a%.0s' $(seq 1 246)).png
"$bin" render "$scenes/shadows.json" -o "$work/$long" --width 16 --height 12 --quiet 2>"$work/err"
check "a 250-character output name" "$([[ $? == 0 && -s "$work/$long" ]] && echo ok || head -c 300 "$work/err")"
finish
