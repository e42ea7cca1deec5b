#!/usr/bin/env bash
# OpenEXR files are written through OpenEXR alone (vkraycast-exr.so, host/image/exr_write.cpp)
# unless VKRAYCAST_EXR_WRITER=oiio asks for OpenImageIO's writer: both make the same file
# (the same header, the same bytes but for the second in capDate, the same pixels) for
# every kind of EXR the renderer writes: an image, its AOVs, the parts of a sharded render,
# a compare heat map. A render to an EXR and `prepare` load no OpenImageIO; a write that
# fails (a full disk, on the image or on its AOVs) is reported, exit status 2, and leaves
# the old files and no temporary behind; so does one through a named temporary, where
# O_TMPFILE is refused (two modules' names at once, a full disk, SIGTERM).
# Usage: test_exr_writer.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
size=(--width 40 --height 28 --quiet)

# `same_file NAME A B`: A and B have the same header (iinfo, capDate aside), the same size,
# bytes that differ only inside capDate's value, and the same pixels.
same_file() {
  local name=$1 a=$2 b=$3 why=ok
  [[ -s $a && -s $b ]] || because "missing: $(ls -l "$a" "$b" 2>&1 | tr '\n' ' ')"
  diff <(iinfo -v "$a" | sed 1d | grep -v DateTime) <(iinfo -v "$b" | sed 1d | grep -v DateTime) >"$work/hdiff" ||
    because "headers differ: $(head -6 "$work/hdiff" | tr '\n' ' ')"
  [[ $(stat -c %s "$a") == $(stat -c %s "$b") ]] || because "sizes $(stat -c %s "$a") and $(stat -c %s "$b")"
  # Offsets (1-based) of the bytes that differ, against capDate's value's 19 bytes.
  local at end off
  at=$(grep -abo 'capDate' "$a" | head -1 | cut -d: -f1)
  [[ -n $at ]] || because "no capDate"
  end=$((at + 8 + 7 + 4 + 19)) # the name, its NUL, "string", its NUL, the size, the value
  for off in $(cmp -l "$a" "$b" 2>/dev/null | awk '{print $1}'); do
    ((off > end - 19 && off <= end)) || { because "byte $off differs"; break; }
  done
  same_pixels "$a" "$b" || because "the pixels differ"
  check "$name" "$why"
}

for w in exr oiio; do
  VKRAYCAST_EXR_WRITER=$w "$bin" render "$scenes/mesh.json" "${size[@]}" -o "$work/$w.exr" \
    --aov "$work/$w.aov.exr" || echo "FAIL: render ($w)"
  for i in 0 1; do
    VKRAYCAST_EXR_WRITER=$w "$bin" render "$scenes/showcase.json" "${size[@]}" --shard $i/2 -o "$work/$w.part$i.exr" ||
      echo "FAIL: part $i ($w)"
  done
  VKRAYCAST_EXR_WRITER=$w "$bin" merge "$work/$w".part{0,1}.exr -o "$work/$w.merged.exr" --quiet || echo "FAIL: merge ($w)"
done
for w in exr oiio; do
  VKRAYCAST_EXR_WRITER=$w "$bin" compare "$work/$w.exr" "$work/oiio.exr" --diff "$work/$w.heat.exr" >/dev/null ||
    echo "FAIL: compare ($w)"
done
same_file "an image" "$work/exr.exr" "$work/oiio.exr"
same_file "its AOVs, named channels" "$work/exr.aov.exr" "$work/oiio.aov.exr"
same_file "a part of a sharded render, its attributes" "$work/exr.part1.exr" "$work/oiio.part1.exr"
same_file "a merged image" "$work/exr.merged.exr" "$work/oiio.merged.exr"
same_file "a heat map (one whole-image write)" "$work/exr.heat.exr" "$work/oiio.heat.exr"
why=ok
[[ $(iinfo -v "$work/exr.part1.exr" | grep -c 'vkraycast:') -ge 5 ]] || because "no vkraycast: attributes"
[[ $(iinfo -v "$work/exr.aov.exr" | grep -c 'channel list: R, G, B, decisions, hit, object, shadow, t') == 1 ]] ||
  because "channels: $(iinfo -v "$work/exr.aov.exr" | grep 'channel list')"
check "the attributes and channel names are there" "$why"

# What the writer is for: a render to EXRs, and prepare, load no OpenImageIO; a forced
# writer loads it.
why=ok
n=$(loads_oiio "$bin" render "$scenes/mesh.json" "${size[@]}" -o "$work/x.exr" --aov "$work/x.aov.exr")
[[ $n == 0 ]] || because "a render to EXRs loaded OpenImageIO ($n)"
n=$(loads_oiio "$bin" prepare "$scenes/mesh.json" -o "$work/x.vkrs" --quiet)
[[ $n == 0 ]] || because "prepare loaded OpenImageIO ($n)"
[[ -s $work/x.vkrs ]] || because "prepare wrote no file"
n=$(VKRAYCAST_EXR_WRITER=oiio loads_oiio "$bin" render "$scenes/mesh.json" "${size[@]}" -o "$work/x.exr")
[[ $n -ge 1 ]] || because "VKRAYCAST_EXR_WRITER=oiio did not load OpenImageIO"
check "renders to EXRs and prepare load OpenEXR alone" "$why"

# A full disk (a 64 KiB file size limit), on the image and, with a small image, on its
# AOVs: exit status 2, the reason, the old files intact, no temporary.
cp "$work/exr.exr" "$work/keep.exr" && cp "$work/exr.aov.exr" "$work/keep.aov.exr"
sums=$(md5sum "$work"/keep.exr "$work"/keep.aov.exr)
for case in "image 256 256" "AOVs 64 96"; do
  read -r what w h <<<"$case"
  why=ok
  bash -c 'ulimit -f 64; exec "$@"' _ "$bin" render "$scenes/mesh.json" --width "$w" --height "$h" --quiet \
    -o "$work/keep.exr" --aov "$work/keep.aov.exr" 2>"$work/err"
  rc=$?
  [[ $rc == 2 ]] || because "exit status $rc"
  grep -q "write failed: File too large" "$work/err" || because "stderr: $(head -c 300 "$work/err")"
  [[ "$(md5sum "$work"/keep.exr "$work"/keep.aov.exr)" == "$sums" ]] || because "an old file changed"
  [[ -z "$(find "$work" -name '.vkraycast-*')" ]] || because "a temporary was left"
  check "a full disk on the $what: refused, old files intact" "$why"
done

# Named temporaries (VKRAYCAST_FAULT=no-tmpfile: a filesystem without O_TMPFILE). A PNG
# and its EXR AOVs are written at once by the two modules, whose counters of temporary
# names share the pid: the second passes over the name the first took. Then a full disk,
# and SIGTERM while the image is written: no temporary is left either way.
temps() { find "$work" -maxdepth 1 -name '.vkraycast-*'; }
why=ok
VKRAYCAST_FAULT=no-tmpfile "$bin" render "$scenes/mesh.json" "${size[@]}" -o "$work/named.png" \
  --aov "$work/named.aov.exr" 2>"$work/err" || because "exit status $?: $(head -c 300 "$work/err")"
same_pixels "$work/named.aov.exr" "$work/exr.aov.exr" || because "the AOVs differ from the unnamed temporary's"
[[ -s $work/named.png ]] || because "no PNG"
[[ -z "$(temps)" ]] || because "left: $(temps)"
check "named temporaries, two modules at once: both files, none left" "$why"
why=ok
VKRAYCAST_FAULT=no-tmpfile bash -c 'ulimit -f 64; exec "$@"' _ "$bin" render "$scenes/mesh.json" --width 256 \
  --height 256 --quiet -o "$work/keep.exr" --aov "$work/keep.aov.exr" 2>"$work/err"
rc=$?
[[ $rc == 2 ]] || because "exit status $rc"
[[ "$(md5sum "$work"/keep.exr "$work"/keep.aov.exr)" == "$sums" ]] || because "an old file changed"
[[ -z "$(temps)" ]] || because "left: $(temps)"
check "named temporaries, a full disk: refused, none left" "$why"
why=ok
VKRAYCAST_FAULT=no-tmpfile "$bin" render "$scenes/showcase.json" -o "$work/keep.exr" --width 1024 --height 1024 \
  --spp 1 --quiet 2>/dev/null &
pid=$!
seen=no
for _ in $(seq 1 1200); do
  [[ -n "$(temps)" ]] && { seen=yes; break; }
  sleep 0.05
done
kill -TERM $pid
wait $pid
rc=$?
[[ $seen == yes ]] || because "never saw the temporary"
[[ $rc == 143 ]] || because "exit status $rc, expected 143"
[[ "$(md5sum "$work"/keep.exr "$work"/keep.aov.exr)" == "$sums" ]] || because "an old file changed"
[[ -z "$(temps)" ]] || because "left: $(temps)"
check "named temporary, SIGTERM while writing: removed" "$why"
finish
