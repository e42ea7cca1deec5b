#!/usr/bin/env bash
# Nothing blocks or spins on special files (issue 13, class 3). Generated: every kind of
# non-regular file (a FIFO with no writer, /dev/zero, /dev/full, a socket, a directory) in
# every role a path plays (scene, mesh named by a scene, a file a mesh names, both inputs
# of compare, a part of merge, image, AOV and statistics outputs, and the band renders'
# image and AOV outputs). Each case must end within 10 s with exit status 2, a
# message naming the path and what it is, and no output file; and /dev/null must still
# be the device afterwards (an output renames over its path).
# Usage: test_special_files.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
mkfifo "$work/fifo"
mkdir "$work/dir"
# A listening Unix socket for the length of the test (python3 ships with Debian 12).
python3 -c 'import socket, sys, time
s = socket.socket(socket.AF_UNIX); s.bind(sys.argv[1]); s.listen(1); time.sleep(120)' "$work/sock" &
sock_pid=$!
trap 'kill $sock_pid 2>/dev/null' EXIT
for _ in $(seq 1 50); do [[ -S $work/sock ]] && break; sleep 0.1; done
"$bin" render "$scenes/shadows.json" -o "$work/good.png" --width 16 --height 12 --quiet

declare -A kinds=([fifo]="$work/fifo" [zero]=/dev/zero [full]=/dev/full [socket]="$work/sock" [dir]="$work/dir")
declare -A words=([fifo]="FIFO" [zero]="character device" [full]="character device" [socket]="socket" [dir]="directory")
run_case() { # name path kind -- command...
  local name=$1 path=$2 kind=$3
  shift 4
  timeout 10 "$@" >"$work/out" 2>"$work/err"
  local got=$? why=ok
  [[ $got == 124 ]] && why="hung (killed after 10 s)"
  [[ $got == 2 || $got == 124 ]] || why="exit status $got, expected 2"
  grep -qF "$path" "$work/err" && grep -q "${words[$kind]}" "$work/err" || why="$why; stderr: $(head -c 200 "$work/err")"
  [[ -z "$(find "$work" -maxdepth 1 -name 'o.*' -o -maxdepth 1 -name 'stats.json')" ]] || why="$why; an output was written"
  rm -f "$work"/o.* "$work/stats.json"
  check "$name" "$why"
}
for kind in "${!kinds[@]}"; do
  p=${kinds[$kind]}
  run_case "scene is $kind" "$p" "$kind" -- "$bin" render "$p" -o "$work/o.png" --quiet
  printf '{ "image": { "width": 8, "height": 6 }, "camera": { "eye": [0, 0, 5], "look_at": [0, 0, 0] },
  "materials": { "m": { "diffuse": [0.5, 0.5, 0.5] } },
  "objects": [ { "type": "mesh", "file": "%s", "material": "m" } ] }\n' "$p" >"$work/mesh_$kind.json"
  run_case "mesh is $kind" "$p" "$kind" -- "$bin" render "$work/mesh_$kind.json" -o "$work/o.png" --quiet \
    --allow-outside-paths
  # A file the mesh names (an OBJ's material library, which assimp looks for in the OBJ's
  # folder: devices through a link there) goes through the same check.
  lib=$(basename "$p")
  [[ $p == /dev/* ]] && lib=link_$kind && ln -sf "$p" "$work/$lib"
  printf 'mtllib %s\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' "$lib" >"$work/mtl_$kind.obj"
  sed "s|\"file\": \"[^\"]*\"|\"file\": \"mtl_$kind.obj\"|" "$work/mesh_$kind.json" >"$work/mtl_$kind.json"
  run_case "material library is $kind" "$lib" "$kind" -- "$bin" render "$work/mtl_$kind.json" -o "$work/o.png" \
    --quiet --allow-outside-paths
  run_case "compare A is $kind" "$p" "$kind" -- "$bin" compare "$p" "$work/good.png"
  run_case "compare B is $kind" "$p" "$kind" -- "$bin" compare "$work/good.png" "$p"
  run_case "image output is $kind" "$p" "$kind" -- "$bin" render "$scenes/shadows.json" -o "$p" --quiet
  run_case "AOV output is $kind" "$p" "$kind" -- "$bin" render "$scenes/shadows.json" -o "$work/o.png" --aov "$p" --quiet
  run_case "statistics output is $kind" "$p" "$kind" -- "$bin" render "$scenes/shadows.json" -o "$work/o.png" \
    --stats-json "$p" --quiet
  # A part of merge, and the outputs of --band-renders (NAME.bandK.EXT beside OUT): the
  # frame itself must not have been written when a band output is refused.
  "$bin" render "$scenes/shadows.json" --shard 0/2 -o "$work/part0.exr" --width 16 --height 12 --quiet
  run_case "merge part is $kind" "$p" "$kind" -- "$bin" merge "$work/part0.exr" "$p" -o "$work/o.png"
  for f in image aov; do
    rm -f "$work/b.png" "$work/b.aov.exr" "$work"/b.band*
    band=$work/b.band2.png
    [[ $f == aov ]] && band=$work/b.aov.band2.exr
    ln -s "$p" "$band"
    timeout 10 "$bin" render "$scenes/shadows.json" -o "$work/b.png" --aov "$work/b.aov.exr" --band-renders 3 \
      --width 16 --height 12 --quiet >"$work/out" 2>"$work/err"
    got=$? why=ok
    [[ $got == 2 ]] || why="exit status $got, expected 2"
    grep -q "${words[$kind]}" "$work/err" || why="$why; stderr: $(head -c 200 "$work/err")"
    [[ ! -e $work/b.png && ! -e $work/b.aov.exr && ! -e $work/b.band1.png ]] || why="$why; outputs written before the refusal"
    rm -f "$band"
    check "band $f output is $kind" "$why"
  done
done
# No output names a file the run reads (issue 45, class 1): every output role against a
# mesh, the material library it names, and a symbolic and a hard link to the mesh; and
# compare's heat map against a --band file. Each refused with exit 2, the input intact.
mkdir -p "$work/in"
printf 'mtllib mats.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$work/in/t.obj"
printf 'newmtl a\nKd 1 0 0\n' >"$work/in/mats.mtl"
printf '{ "image": {"width": 8, "height": 8}, "camera": {"eye": [0,0,5], "look_at": [0,0,0]},
  "objects": [{"type": "mesh", "file": "t.obj"}]}\n' >"$work/in/t.json"
ln -sf t.obj "$work/in/sym.png"
ln -f "$work/in/t.obj" "$work/in/hard.exr"
cp "$work/in/t.obj" "$work/t.obj.orig"
cp "$work/in/mats.mtl" "$work/mats.orig"
for input in t.obj mats.mtl sym.png hard.exr; do
  for role in image aov stats band; do
    case $role in
      image) args=(-o "$work/in/$input") ;;
      aov) args=(-o "$work/in/o.png" --aov "$work/in/$input") ;;
      stats) args=(-o "$work/in/o.png" --stats-json "$work/in/$input") ;;
      band) [[ $input == *.png ]] || continue
            ln -sf t.obj "$work/in/b.band1.png"; args=(-o "$work/in/b.png" --band-renders 1) ;;
    esac
    timeout 30 "$bin" render "$work/in/t.json" "${args[@]}" --quiet >/dev/null 2>"$work/err"
    got=$? why=ok
    [[ $got == 2 ]] || why="exit status $got, expected 2"
    cmp -s "$work/in/t.obj" "$work/t.obj.orig" && cmp -s "$work/in/mats.mtl" "$work/mats.orig" || why="$why; an input changed"
    [[ ! -e $work/in/o.png && ! -e $work/in/b.png ]] || why="$why; an output was written"
    grep -q "name the same file\|no image format\|need a multi-channel" "$work/err" || why="$why; stderr: $(head -c 200 "$work/err")"
    rm -f "$work/in/o.png" "$work/in/b.png" "$work/in/b.band1.png"
    check "$role output names the scene's input $input" "$why"
  done
done
"$bin" render "$scenes/shadows.json" -o "$work/ref.exr" --aov "$work/ref.aov.exr" --width 16 --height 12 --quiet
cp "$work/ref.aov.exr" "$work/band.aov.exr"
timeout 30 "$bin" compare "$work/ref.aov.exr" "$work/ref.aov.exr" --band "$work/band.aov.exr" --diff "$work/band.aov.exr" \
  >/dev/null 2>"$work/err"
check "compare --diff names a --band file" \
  "$([[ $? == 2 ]] && grep -q "name the same file" "$work/err" && cmp -s "$work/ref.aov.exr" "$work/band.aov.exr" &&
     echo ok || cat "$work/err")"
check "/dev/null is still a character device" "$([[ -c /dev/null ]] && echo ok || echo 'it was replaced')"
finish
