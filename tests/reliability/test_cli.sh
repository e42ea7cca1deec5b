#!/usr/bin/env bash
# The command-line conventions of docs/cli.md (issue 17): every option of `render --help`
# is accepted in both spellings; options before the subcommand; `-` and pipes as the
# scene; `--stats-json -`; refusals of `-o -`; one usage line for a usage error; statistics
# true to the backend that ran; --version naming what it was built with.
# Usage: test_cli.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
S=$scenes/shadows.json
small=(--width 24 --height 16 --quiet)

# A reference render, and the same scene by every way of naming the input.
"$bin" render "$S" -o "$work/ref.png" "${small[@]}" || check "reference render" "exit status $?"
same() { # NAME FILE: FILE exists and equals the reference
  check "$1" "$([[ -s $2 ]] && cmp -s "$work/ref.png" "$2" && echo ok || echo "missing or different")"
}
"$bin" render - -o "$work/stdin.png" "${small[@]}" <"$S"
same "render - (redirected file)" "$work/stdin.png"
cat "$S" | "$bin" render - -o "$work/pipe.png" "${small[@]}"
same "render - (pipe)" "$work/pipe.png"
cat "$S" | "$bin" render /dev/stdin -o "$work/devstdin.png" "${small[@]}"
same "render /dev/stdin (pipe)" "$work/devstdin.png"
"$bin" render <(cat "$S") -o "$work/procsub.png" "${small[@]}"
same "render <(...) (process substitution)" "$work/procsub.png"
mkfifo "$work/fifo"
(cat "$S" >"$work/fifo") &
timeout 20 "$bin" render "$work/fifo" -o "$work/fifo.png" "${small[@]}"
same "render FIFO with a writer" "$work/fifo.png"
# A stream has no extension: '{' first means JSON, anything else the .test format.
T=$(dirname "$0")/../fuzz/corpus/test/small.test
"$bin" render "$T" -o "$work/t_file.png" --quiet && "$bin" render - -o "$work/t_stdin.png" --quiet <"$T"
check "a .test scene on standard input" \
  "$([[ -s $work/t_file.png ]] && cmp -s "$work/t_file.png" "$work/t_stdin.png" && echo ok || echo differs)"
"$bin" render - -o "$work/empty.png" "${small[@]}" </dev/null 2>"$work/err"
check "render - with nothing on stdin: exit 2, says empty" \
  "$([[ $? == 2 ]] && grep -q '<stdin>: error: the scene is empty' "$work/err" && echo ok || cat "$work/err")"
printf '{ "image": { "width": 8, "height": 6 },\n  "camera": { "eye": [0, 0, 5], "look_at": [0, 0' |
  "$bin" render - -o "$work/trunc.png" --quiet 2>"$work/err"
check "truncated JSON on stdin names <stdin> and the end of input" \
  "$(grep -q '<stdin>:2:49: error: JSON syntax: unexpected end of input inside the array opened at 2:44' "$work/err" &&
     echo ok || cat "$work/err")"

# Options: --opt=value, options before the subcommand, -q.
"$bin" --backend=gpu render --output="$work/eq.png" --width=24 --height=16 -q "$S"
same "--opt=value and options before the subcommand" "$work/eq.png"
"$bin" render -o="$work/short_eq.png" "$S" --width 24 --height 16 --quiet
same "-o=value" "$work/short_eq.png"
# Every option the help lists is known to the parser (one table drives both).
"$bin" render --help >"$work/help.txt"
opts=$(grep -oE '^ +(-[a-z], )?--[a-z0-9-]+' "$work/help.txt" | sed -E 's/.*(--[a-z0-9-]+)$/\1/' | sort -u)
n=0
for o in $opts; do
  n=$((n + 1))
  "$bin" render "$S" -o "$work/x.png" "$o" 2>"$work/err" >/dev/null
  if grep -q "unknown option" "$work/err"; then check "render --help lists $o" "the parser does not know it"; fi
done
check "render --help lists options" "$([[ $n -ge 28 ]] && echo ok || echo "only $n")"

# A usage error: the problem and one usage line, not the whole help.
"$bin" render "$S" 2>"$work/err"
check "missing -o: exit 2, three lines" \
  "$([[ $? == 2 && $(wc -l <"$work/err") == 3 ]] && grep -q 'no output file given (-o OUT)' "$work/err" &&
     grep -q '^usage: vkraycast render SCENE -o OUT \[options\]$' "$work/err" && echo ok || cat "$work/err")"

# A .test scene's `output` command names the image when -o does not, in the current
# folder; -o wins over it.
mkdir -p "$work/course"
printf 'size 24 16\noutput course.png\ncamera 0 0 5 0 0 0 0 1 0 45\nambient .2 .2 .2\nsphere 0 0 0 1\n' \
  >"$work/course/scene.test"
(cd "$work/course" && "$bin" render scene.test --quiet 2>"$work/err")
check ".test output command honoured" "$([[ -s $work/course/course.png ]] && echo ok || cat "$work/err")"
(cd "$work/course" && "$bin" render scene.test -o other.png --quiet 2>"$work/err")
check "-o wins over the .test output command" \
  "$([[ -s $work/course/other.png && $(find "$work/course" -newer "$work/course/course.png" -name course.png | wc -l) == 0 ]] &&
     echo ok || cat "$work/err")"

# Control characters from the user's input never reach the terminal raw (the filtered
# streams of host/cli/safe_streams.h): ESC, CR, BEL, DEL and SOH in a material name, an
# unknown key, a scene path and an option value, each must come out spelled \xNN.
for code in 1b 0d 07 7f 01; do
  c=$(printf "\\x$code")
  printf '{ "image": {"width": 8, "height": 8}, "camera": {"eye": [0,0,5], "look_at": [0,0,0]},
  "materials": {"m\\u00%sx": {"diffuse": [1,1,1]}},
  "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "n\\u00%sx"}]}\n' "$code" "$code" \
    >"$work/ctl.json"
  printf '{ "image": {"width": 8, "height": 8, "k\\u00%sy": 1} }\n' "$code" >"$work/ctl_key.json"
  for role in material key path option; do
    case $role in
      material) "$bin" render "$work/ctl.json" -o "$work/ctl.png" 2>"$work/err" ;;
      key) "$bin" render "$work/ctl_key.json" -o "$work/ctl.png" 2>"$work/err" ;;
      path) "$bin" render "$work/no${c}such.json" -o "$work/ctl.png" 2>"$work/err" ;;
      option) "$bin" render "$S" -o "$work/ctl.png" --backend "g${c}pu" 2>"$work/err" ;;
    esac
    check "control character 0x$code in a $role is escaped" \
      "$(! grep -q "$c" "$work/err" && grep -qF "\\x$code" "$work/err" && echo ok || cat -v "$work/err")"
  done
done

# --stats-json - writes the statistics to standard output; -o - is refused before reading.
"$bin" render "$S" -o "$work/s.png" --stats-json - "${small[@]}" >"$work/stats.json"
check "--stats-json - is JSON on stdout" \
  "$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print("ok" if d["width"] == 24 else d)' \
     "$work/stats.json" 2>&1)"
[[ -e $work/- ]] && check "--stats-json - wrote no file named -" "it did"
"$bin" render "$S" -o - "${small[@]}" 2>"$work/err"
check "-o - refused" "$([[ $? == 2 ]] && grep -q 'not written to standard output' "$work/err" && echo ok || cat "$work/err")"

# Statistics true to the backend: the CPU's have no GPU-only fields; both name the
# program version and the scene; max_dispatch_ms is the one dispatch's time for one tile.
"$bin" render "$S" -o "$work/c.png" --backend cpu --stats-json "$work/cpu.json" "${small[@]}"
python3 - "$work/cpu.json" "$S" <<'PY' >"$work/py.out" 2>&1
import json, sys
d = json.load(open(sys.argv[1]))
gpu_only = [k for k in ("pipeline", "scene_buffers", "staging", "upload_ms", "pipeline_ms", "tiles", "dispatches",
                        "max_dispatch_ms", "loop_budget", "subgroup_size", "readback_ms") if k in d]
bad = gpu_only or d["backend"] != "cpu" or not d["vkraycast"].startswith("0.") or d["scene"] != sys.argv[2]
print("ok" if not bad else (gpu_only, d["vkraycast"], d["scene"]))
PY
check "CPU statistics: no GPU-only fields; the version and the scene" "$(cat "$work/py.out")"
for tile in "--tile 1024" "--tile 8"; do
  # shellcheck disable=SC2086
  "$bin" render "$S" -o "$work/t.png" $tile --stats-json "$work/tile.json" "${small[@]}"
  python3 - "$work/tile.json" <<'PY' >"$work/py.out" 2>&1
import json, sys
d = json.load(open(sys.argv[1]))
ok = d["max_dispatch_ms"] > 0 and d["max_dispatch_ms"] <= d["render_ms"] + 1e-9 and "pipeline" in d
print("ok" if ok else (d["max_dispatch_ms"], d["render_ms"], d["tiles"]))
PY
  check "GPU statistics $tile: 0 < max_dispatch_ms <= render_ms" "$(cat "$work/py.out")"
done

# Every render setting that changes pixels lives in the scene too, and the command line
# overrides it: quality.shadows and --shadows, image.encoding and --encoding/--srgb,
# image.quantize and --quantize. Each pair gives byte-identical PNGs; the settings are
# chosen where they change the image (checked against the defaults).
scene_with() { # FILE SED-EXPR: shadows.json edited
  sed "$2" "$S" >"$1"
}
scene_with "$work/noshadow.json" 's/"quality": *{/&"shadows": false, /; t; s/^{/{"quality": {"shadows": false},/'
scene_with "$work/srgb.json" 's/"image": *{/&"encoding": "srgb", "quantize": "truncate", /'
"$bin" render "$work/noshadow.json" -o "$work/q_scene.png" "${small[@]}"
"$bin" render "$S" -o "$work/q_cli.png" --shadows off "${small[@]}"
check "quality.shadows false = --shadows off, and differs from shadows on"   "$(cmp -s "$work/q_scene.png" "$work/q_cli.png" && ! cmp -s "$work/q_scene.png" "$work/ref.png" && echo ok || echo differs)"
"$bin" render "$work/noshadow.json" -o "$work/q_back.png" --shadows on "${small[@]}"
same "--shadows on overrides quality.shadows false" "$work/q_back.png"
"$bin" render "$work/srgb.json" -o "$work/e_scene.png" "${small[@]}"
"$bin" render "$S" -o "$work/e_cli.png" --srgb --quantize truncate "${small[@]}"
check "image.encoding srgb + quantize truncate = --srgb --quantize truncate, and differ from the defaults" \
  "$(cmp -s "$work/e_scene.png" "$work/e_cli.png" && ! cmp -s "$work/e_scene.png" "$work/ref.png" && echo ok || echo differs)"
"$bin" render "$work/srgb.json" -o "$work/e_back.png" --encoding linear --quantize round "${small[@]}"
same "--encoding linear --quantize round override the scene's image settings" "$work/e_back.png"
# The course's display conventions: a pure gamma and an exposure in stops, from the scene
# or the command line, alike; float outputs keep the linear value whatever they say.
scene_with "$work/gamma.json" 's/"image": *{/&"encoding": "gamma", "gamma": 2.2, "exposure": 0.5, /'
"$bin" render "$work/gamma.json" -o "$work/g_scene.png" "${small[@]}"
"$bin" render "$S" -o "$work/g_cli.png" --gamma 2.2 --exposure 0.5 "${small[@]}"
check "image.encoding gamma, gamma 2.2, exposure 0.5 = --gamma 2.2 --exposure 0.5, and differ from the defaults" \
  "$(cmp -s "$work/g_scene.png" "$work/g_cli.png" && ! cmp -s "$work/g_scene.png" "$work/ref.png" && echo ok || echo differs)"
"$bin" render "$work/gamma.json" -o "$work/g_back.png" --encoding linear --exposure 0 "${small[@]}"
same "--encoding linear --exposure 0 override the scene's gamma and exposure" "$work/g_back.png"
"$bin" render "$work/gamma.json" -o "$work/g_scene.exr" "${small[@]}"
"$bin" render "$S" -o "$work/g_plain.exr" "${small[@]}"
"$bin" compare "$work/g_scene.exr" "$work/g_plain.exr" --fail 0 >"$work/g_cmp.txt" 2>&1
check "an EXR holds the linear value whatever the 8-bit encoding" "$([[ $? == 0 ]] && echo ok || head -5 "$work/g_cmp.txt")"

# OpenImageIO (and its ~260 libraries) is loaded at the first image it must handle, not
# before (host/image/image_module.h): --help, --version, a refused command line and a scene
# refused at parse never load it; a render to a format only it writes (.tif) does, to check
# that its output names a format it writes: before the scene and its meshes are read where
# the name is not a common one (so that such a scene is not read for nothing), after where
# it is (host/cli/output.h); a render to .png or .exr never does (png_write.c in the binary,
# vkraycast-exr.so); and a binary whose module is missing says so and exits 3 where it needs
# it, and still writes a PNG.
# (By its soname, or by its path where image_load.c loads the module's libraries first.)
sed 's/"radius": *[0-9.]*/"radius": -1/' "$S" >"$work/bad_radius.json"
check "--version, --help and a refused command line do not load OpenImageIO" \
  "$(n=$(( $(loads_oiio "$bin" --version) + $(loads_oiio "$bin" render --help) +
          $(loads_oiio "$bin" render "$work/bad_radius.json" -o "$work/x.png" --spp 0) )); [[ $n == 0 ]] && echo ok || echo "$n loads")"
check "a scene refused at parse does not load OpenImageIO (.png, .exr)" \
  "$(n=$(( $(loads_oiio "$bin" render "$work/bad_radius.json" -o "$work/x.png") +
          $(loads_oiio "$bin" render "$work/bad_radius.json" -o "$work/x.exr") )); [[ $n == 0 ]] && echo ok || echo "$n loads")"
"$bin" render "$work/bad_radius.json" -o "$work/x.foo" 2>"$work/err"
check "the output's format is checked before the scene is read" \
  "$([[ $? == 2 ]] && grep -q 'x.foo: no image format' "$work/err" && ! grep -q radius "$work/err" && echo ok || cat "$work/err")"
check "a render to a TIFF loads OpenImageIO" \
  "$([[ $(loads_oiio "$bin" render "$S" -o "$work/oiio.tif" "${small[@]}") -ge 1 ]] && echo ok || echo "not loaded")"
check "a render to a PNG or an EXR does not" \
  "$(n=$(( $(loads_oiio "$bin" render "$S" -o "$work/x.png" "${small[@]}") +
          $(loads_oiio "$bin" render "$S" -o "$work/x.exr" "${small[@]}") )); [[ $n == 0 ]] && echo ok || echo "$n loads")"
mkdir -p "$work/lonely" && cp "$bin" "$work/lonely/vkraycast"
"$work/lonely/vkraycast" render "$S" -o "$work/lonely.tif" "${small[@]}" 2>"$work/err"
check "a binary without its image module: exit 3 for a TIFF, names the module, writes nothing" \
  "$([[ $? == 3 && ! -e $work/lonely.tif ]] && grep -q 'cannot load the image module .*vkraycast-image.so' "$work/err" && echo ok || cat "$work/err")"
"$work/lonely/vkraycast" render "$S" -o "$work/lonely.png" "${small[@]}" 2>"$work/err"
check "a binary without its image modules still writes a PNG" \
  "$([[ $? == 0 ]] && same_pixels "$work/lonely.png" "$work/x.png" && echo ok || cat "$work/err")"

# --band-renders: the frame and its conditioning band in one process, each band file
# bit for bit the render that --perturb K alone makes.
B=(--width 24 --height 16 --quiet --backend cpu)
"$bin" render "$S" -o "$work/band.exr" --aov "$work/band.aov.exr" --band-renders 2 --stats-json "$work/band.json" "${B[@]}"
got=$? why=ok
[[ $got == 0 ]] || because "exit status $got"
for k in 1 2; do
  "$bin" render "$S" -o "$work/alone$k.exr" --aov "$work/alone$k.aov.exr" --perturb $k "${B[@]}"
  "$bin" compare "$work/band.band$k.exr" "$work/alone$k.exr" --fail 0 >/dev/null 2>&1 || because "band $k image differs"
  "$bin" compare "$work/band.aov.band$k.exr" "$work/alone$k.aov.exr" --fail 0 --depth-tolerance 0 \
    --normal-tolerance 0 >/dev/null 2>&1 || because "band $k AOVs differ"
done
"$bin" compare "$work/band.band1.exr" "$work/band.exr" --fail 0 >/dev/null 2>&1 && because "band 1 equals the unperturbed frame"
[[ ! -e $work/band.band3.exr && $(json_num repeat "$work/band.json") == 1 ]] || because "a third band, or no statistics"
check "--band-renders 2: NAME.bandK.EXT equal to --perturb K renders" "$why"
expect_exit2 "--band-renders with --perturb" "$work/bp.png" "--band-renders and --perturb" \
  "$bin" render "$S" -o "$work/bp.png" --band-renders 2 --perturb 3 "${B[@]}"
expect_exit2 "a band image naming the AOV file" "$work/clash.exr" "name the same file" \
  "$bin" render "$S" -o "$work/clash.exr" --aov "$work/clash.band1.exr" --band-renders 1 "${B[@]}"
# A bad --region or --shard is quoted in the message, never read as a format string.
expect_exit2 "--region with conversion specifiers, quoted" "$work/pct.png" "--region %n%s%n%s: expected" \
  "$bin" render "$S" -o "$work/pct.png" --region '%n%s%n%s' "${B[@]}"
expect_exit2 "--shard with conversion specifiers, quoted" "$work/pct.exr" "--shard %n%s/%n:" \
  "$bin" render "$S" -o "$work/pct.exr" --shard '%n%s/%n' "${B[@]}"

# --version: the program, and what it was built and runs with.
"$bin" --version >"$work/version.txt"
# The CPU backend's SIMD model (simd8_efficiency, docs/cli.md): exactly 1 where every pixel
# takes the same steps (one sphere behind the eye: each primary ray tests the root's box
# and misses); below 1 where neighbours diverge (a cloud of small spheres), and the same for
# any number of threads (vectors are 8 pixels of a row, whichever thread rendered it).
cat >"$work/behind.json" <<'JSON'
{ "image": { "width": 24, "height": 16 }, "camera": { "eye": [0, 0, 5], "look_at": [0, 0, 0] },
  "materials": { "m": { "diffuse": [0.5, 0.5, 0.5] } },
  "lights": [ { "type": "point", "position": [0, 4, 4], "intensity": [9, 9, 9] } ],
  "objects": [ { "type": "sphere", "center": [0, 0, 9], "radius": 1, "material": "m" } ] }
JSON
"$(dirname "$0")/../../tools/gen_sphere_cloud.sh" 300 >"$work/cloud.json"
model() { "$bin" render "$1" -o "$work/model.png" --backend cpu --eye-buffer off --quiet --stats-json "$work/model.json" \
  --allow-outside-paths "${@:2}" && json_num simd8_efficiency "$work/model.json"; }
e=$(model "$work/behind.json")
check "SIMD model: lanes of equal work keep every lane busy" "$([[ $e == 1 ]] && echo ok || echo "simd8_efficiency $e")"
e1=$(model "$work/cloud.json" --width 64 --height 48 --threads 1)
e2=$(model "$work/cloud.json" --width 64 --height 48 --threads 2)
check "SIMD model: a cloud of spheres diverges, the same on 1 and 2 threads" \
  "$(awk -v a="$e1" -v b="$e2" 'BEGIN { print (a > 0.3 && a < 0.95 && a == b) ? "ok" : "simd8_efficiency " a " and " b }')"
check "--version names the loader and the shader compiler" \
  "$(grep -q '^vkraycast [0-9]' "$work/version.txt" && grep -q 'Vulkan headers' "$work/version.txt" &&
     grep -q 'glslangValidator' "$work/version.txt" && grep -q 'running with: Vulkan loader' "$work/version.txt" &&
     echo ok || cat "$work/version.txt")"
finish
