#!/usr/bin/env bash
# Whether two builds render the same pixels: each scene on both backends and in both
# precisions, colour and AOVs, by OLD and NEW, compared with no tolerance at all. For
# refactorings that must change no image (a moved file, a function split in the shader and
# its twin). Prints one line per scene; exits 1 on any difference.
#   tools/same_images.sh OLD_VKRAYCAST NEW_VKRAYCAST WORKDIR SCENE...
# (Copy the old build's vkraycast and vkraycast-image.so to a folder of their own first.)
set -uo pipefail
old=$1 new=$2 work=$3
shift 3
mkdir -p "$work"
size=(--width 128 --height 96 --quiet --allow-outside-paths)
failed=0
for scene in "$@"; do
  name=$(basename "$scene" .json) verdict=same
  for variant in "gpu f32" "gpu f64" "cpu f32" "cpu f64"; do
    read -r backend precision <<<"$variant"
    out=$work/$name-$backend-$precision
    for build in old new; do
      bin=$old
      [[ $build == new ]] && bin=$new
      "$bin" render "$scene" -o "$out-$build.exr" --aov "$out-$build.aov.exr" --backend "$backend" \
        --precision "$precision" "${size[@]}" 2>/dev/null || verdict="$verdict; $variant $build: render failed"
    done
    "$new" compare "$out-old.exr" "$out-new.exr" --fail 0 >/dev/null 2>&1 || verdict="$verdict; $variant: colour differs"
    "$new" compare "$out-old.aov.exr" "$out-new.aov.exr" --fail 0 --depth-tolerance 0 --normal-tolerance 0 \
      >/dev/null 2>&1 || verdict="$verdict; $variant: AOVs differ"
  done
  [[ $verdict == same ]] || failed=1
  echo "$name: $verdict"
done
exit $failed
