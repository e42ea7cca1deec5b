#!/usr/bin/env bash
# Whether two builds write the same 8-bit files: each scene under several encodings and
# settings, rendered as PNG by OLD and by NEW with --gpu-encode auto and off, compared
# byte for byte (docs/numerics.md §11). Prints one line per difference and one per scene;
# exits 1 on any difference.
#   tools/same_levels.sh OLD_VKRAYCAST NEW_VKRAYCAST WORKDIR SCENE...
# (Copy the old build's vkraycast and vkraycast-image.so to a folder of their own first.
# An OLD from before --gpu-encode existed is run without it.)
set -uo pipefail
old=$1 new=$2 work=$3
shift 3
mkdir -p "$work"
variants=("" "--encoding srgb" "--gamma 1.8 --exposure 1.5" "--quantize truncate" "--spp 3 --exposure -2"
          "--staging --tile 64 --encoding srgb" "--backend cpu --threads 2")
failed=0
for scene in "$@"; do
  name=$(basename "$scene" .json)
  for i in "${!variants[@]}"; do
    read -ra v <<<"${variants[$i]}"
    out=$work/$name-$i
    "$old" render "$scene" -o "$out-old.png" --width 160 --height 100 -q "${v[@]}" 2>/dev/null ||
      echo "$name [${variants[$i]}]: old failed"
    for mode in auto off; do
      "$new" render "$scene" -o "$out-$mode.png" --width 160 --height 100 -q --gpu-encode $mode "${v[@]}" \
        2>/dev/null || echo "$name [${variants[$i]}]: $mode failed"
      cmp -s "$out-old.png" "$out-$mode.png" || { echo "$name [${variants[$i]}]: $mode differs"; failed=1; }
    done
  done
  echo "$name done"
done
exit $failed
