#!/usr/bin/env bash
# Readers that cannot crash the program (issue 45, class 4). Generated broken meshes of
# every format assimp reads for us (OBJ, PLY ASCII and binary, OFF, STL ASCII and binary,
# glTF, GLB): indices past the vertex arrays, negative and overflowing indices, headers
# that declare more than the file holds, truncated binaries. Each render must end within
# 30 s with exit status 2, a message naming the mesh file, and no output; a signal is a
# failure. And compare's inputs: images of 1, 2, 4, 5 and 70 channels, a tiled EXR and a
# two-part EXR, against themselves and a plain one: a verdict or a clear refusal (exit
# 2), never a signal. Outside sanitizer builds both run under a 4 GiB address-space limit,
# so that a reader which trusts a declared count runs out of memory instead of the host.
# Usage: test_readers.sh VKRAYCAST WORKDIR
set -uo pipefail
bin=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
# The limit where the binary starts under it (a sanitizer build reserves terabytes of
# address space for its shadow memory and does not).
limited=0
(ulimit -v 4194304 && "$bin" --version >/dev/null 2>&1) && limited=1
limit() { if ((limited)); then (ulimit -v 4194304 && "$@"); else "$@"; fi; }

python3 - "$work" <<'PY'
import base64, json, struct, sys
w = sys.argv[1]
def put(name, data):
    open(f"{w}/{name}", "wb").write(data if isinstance(data, bytes) else data.encode())
tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
put("obj_index_past_end.obj", tri + "f 1 2 99999999\n")
put("obj_index_negative.obj", tri + "f -1 -2 -99999999\n")
put("obj_index_overflow.obj", tri + "f 1 2 4294967297\n")
put("obj_index_zero.obj", tri + "f 0 1 2\n")
put("obj_vertex_nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
# Found by the fuzzer: a material library with a map statement before any newmtl killed
# assimp 5.2.4 with SIGSEGV; every statement that sets a map, and an OBJ that names
# itself as its library with a map statement in it.
for kw in ["map_Ka", "map_Kd", "map_Ks", "map_Ke", "map_d", "map_Ns", "map_bump", "bump", "bumpy", "disp", "refl",
           "norm", "map_Pr", "map_Pm", "map_Ps", "map_Kdx", "bUMP", "a", "aniso"]:
    put(f"obj_mtl_{kw}.mtl", f"# a library\n\n{kw}{'' if kw == 'a' else ' texture.png'}\nnewmtl m\nKd 1 1 1\n")
    put(f"obj_mtl_{kw}.obj", f"mtllib obj_mtl_{kw}.mtl\n" + tri + "usemtl m\nf 1 2 3\n")
# Lines as assimp cuts them: a lone CR, a form feed or a NUL ends one too, and blanks
# before a statement do not hide it (found by the fuzzer: "OFF\n5\r\r...map_Kn").
for tag, sep in [("cr", "\r"), ("ff", "\f"), ("nul", "\0"), ("crlf", "\r\n")]:
    put(f"obj_mtl_{tag}_lines.mtl", f"# a library{sep}5{sep}{sep} \t map_Kd x.png{sep}newmtl m{sep}")
    put(f"obj_mtl_{tag}_lines.obj", f"mtllib obj_mtl_{tag}_lines.mtl\n" + tri + "f 1 2 3\n")
put("obj_mtllib_itself.obj", "mtllib obj_mtllib_itself.obj\n" + tri + "map_Kd texture.png\nf 1 2 3\n")
put("obj_mtllib_itself_dot.obj", "mtllib  ./obj_mtllib_itself_dot.obj \n" + tri + "bump x\nf 1 2 3\n")
# Files whose content assimp reads as an OBJ whatever their name (it picks an importer
# by content when the extension's declines), naming such a library (found by the fuzzer
# through a .gltf file).
for ext in ["gltf", "stl", "dae"]:
    put(f"obj_content_as_{ext}.mtl", "# a library\nbump b.png\nnewmtl m\n")
    put(f"obj_content_as.{ext}", f"mtllib obj_content_as_{ext}.mtl\n" + tri + "f 1 2 3\n")
# And a library that is fine: its maps after newmtl (control, renders).
put("good_mtl.mtl", "# ok\nnewmtl m\nKd 1 0.5 0.5\nmap_Kd texture.png\nbump b.png\n")
put("good_mtl.obj_", "mtllib good_mtl.mtl\n" + tri + "usemtl m\nf 1 2 3\n")
head = "ply\nformat {fmt} 1.0\nelement vertex {nv}\nproperty float x\nproperty float y\nproperty float z\n" \
       "element face {nf}\nproperty list uchar int vertex_indices\nend_header\n"
verts = "0 0 0\n1 0 0\n0 1 0\n"
put("ply_index_2e9.ply", head.format(fmt="ascii", nv=3, nf=1) + verts + "3 0 1 2000000000\n")
put("ply_index_negative.ply", head.format(fmt="ascii", nv=3, nf=1) + verts + "3 0 1 -5\n")
put("ply_vertex_count_2e9.ply", head.format(fmt="ascii", nv=2000000000, nf=1) + verts + "3 0 1 2\n")
put("ply_face_count_2e9.ply", head.format(fmt="ascii", nv=3, nf=2000000000) + verts + "3 0 1 2\n")
put("ply_list_count_255.ply", head.format(fmt="ascii", nv=3, nf=1) + verts + "255 0 1 2\n")
binv = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
put("ply_binary_index_2e9.ply", head.format(fmt="binary_little_endian", nv=3, nf=1).encode() + binv +
    struct.pack("<B3i", 3, 0, 1, 2000000000))
put("ply_binary_count_2e9.ply", head.format(fmt="binary_little_endian", nv=2000000000, nf=1).encode() + binv)
# A valid binary PLY whose data begins with the byte 0x0A: assimp 5.2.4 reads it as the
# header's line end, misreads the rest and aborts in an assertion (SIGABRT).
put("ply_binary_data_starts_lf.ply", head.format(fmt="binary_little_endian", nv=3, nf=1).encode() +
    struct.pack("<9f", struct.unpack("<f", b"\na\x20\x40")[0], 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<B3i", 3, 0, 1, 2))
put("ply_binary_truncated.ply", head.format(fmt="binary_little_endian", nv=3, nf=1).encode() + binv[:20])
put("off_index_past_end.off", "OFF\n3 1 0\n" + verts + "3 0 1 77777777\n")
put("off_counts_1e9.off", "OFF\n3 1000000000 0\n" + verts + "3 0 1 2\n")
# Found by the fuzzer: the counts, then no third number but bytes assimp skips.
put("off_counts_then_garbage.off", b"OFF\n3 1000000000 " + b"\xa3" * 89 + b"0\n0 0 0\n1\n")
# Found by the fuzzer: OFF and PLY headers in files of other names, which assimp reads by
# their content when the extension's importer declines them.
put("off_in_gltf.gltf", b"OFF\n3 1000000000 " + b"\xa3" * 60 + b"0\n1\n")
put("ply_in_obj.obj", head.format(fmt="ascii", nv=2000000000, nf=1) + verts + "3 0 1 2\n")
put("noff_counts_1e9.off", "NOFF\n3 1000000000 0\n" + verts + "3 0 1 2\n")
# Found by the fuzzer: the importer reads a count glued to "OFF" and wraps one past 2^32
# (2.6 billion faces, 42 GB asked for); comments between the counts; the n-dimensional
# header; an index out of range after a comment and on a 4OFF (homogeneous) vertex list.
put("off_count_glued_wraps.off", "OFF1 3000000000000000010000")
put("off_comment_between_counts.off", "OFF\n# a comment\n3 # and one more\n1000000000 0\n" + verts + "3 0 1 2\n")
put("noff_dimension_counts.off", "nOFF\n3\n3 1000000000 0\n" + verts + "3 0 1 2\n")
put("off_comment_index_past_end.off", "OFF\n#c\n3 1 0\n" + verts + "3 0 1 3\n")
put("4off_index_past_end.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 9\n")
put("stl_binary_count_4e9.stl", b"\0" * 80 + struct.pack("<I", 0xFFFFFFFF) + b"\0" * 50)
put("stl_binary_truncated.stl", b"\0" * 80 + struct.pack("<I", 2) + b"\0" * 60)
put("stl_ascii_nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
    "endloop\nendfacet\nendsolid x\n")
# glTF: one triangle, its buffer inline; then each lie a header can tell.
buf = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
def gltf(index_max=2, count=3, view_len=36, byte_len=None, indices=(0, 1, 2)):
    b = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", *indices) + b"\0\0"
    return {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "scene": 0, "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "buffers": [{"byteLength": byte_len or len(b),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(b).decode()}],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": view_len},
                            {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 0]},
                          {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}
put("gltf_index_past_end.gltf", json.dumps(gltf(indices=(0, 1, 60000))))
put("gltf_count_2e9.gltf", json.dumps(gltf(count=2000000000)))
put("gltf_view_past_buffer.gltf", json.dumps(gltf(view_len=4000000)))
put("gltf_buffer_length_lie.gltf", json.dumps(gltf(byte_len=2000000000)))
g = json.dumps(gltf()).encode()
g += b" " * (-len(g) % 4)
put("glb_length_lie.glb", struct.pack("<III", 0x46546C67, 2, 2000000000) + struct.pack("<II", len(g), 0x4E4F534A) + g)
put("glb_chunk_length_lie.glb", struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(g)) +
    struct.pack("<II", 2000000000, 0x4E4F534A) + g)
put("glb_truncated.glb", struct.pack("<III", 0x46546C67, 2, 1000)[:10])
PY

for mesh in "$work"/*.obj "$work"/*.ply "$work"/*.off "$work"/*.stl "$work"/*.gltf "$work"/*.glb "$work"/*.dae; do
  name=$(basename "$mesh")
  printf '{ "image": {"width": 8, "height": 8}, "camera": {"eye": [0,0,5], "look_at": [0,0,0]},
  "materials": {"m": {"diffuse": [1,1,1]}},
  "objects": [{"type": "mesh", "file": "%s", "material": "m"}]}\n' "$name" >"$work/scene.json"
  rm -f "$work/o.png"
  limit timeout 30 "$bin" render "$work/scene.json" -o "$work/o.png" --backend cpu --quiet >/dev/null 2>"$work/err"
  got=$? why=ok
  ((got == 124)) && why="hung (killed after 30 s)"
  ((got > 128 && got != 124)) && why="killed by signal $((got - 128))"
  [[ $why == ok && $got != 2 ]] && why="exit status $got, expected 2"
  grep -qF "$name" "$work/err" || why="$why; stderr does not name the file: $(head -c 200 "$work/err")"
  [[ ! -e $work/o.png ]] || why="$why; an image was written"
  check "mesh $name" "$why"
done
# The controls: an OBJ whose library is well formed renders, and so does a glTF whose
# buffer is a file of its own (binary: read through the same check).
python3 - "$work" <<'PY'
import json, struct, sys
w = sys.argv[1]
b = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2) + b"\0\0"
open(f"{w}/good_buffer.bin", "wb").write(b)
g = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "scene": 0, "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
     "buffers": [{"byteLength": len(b), "uri": "good_buffer.bin"}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                   {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}
open(f"{w}/good_buffer.gltf_", "w").write(json.dumps(g))
PY
mv "$work/good_buffer.gltf_" "$work/good_buffer.gltf"
expect_renders() { # NAME MESH: the scene with MESH as its mesh renders, exit 0 and an image
  sed "s/\"file\": \"[^\"]*\"/\"file\": \"$2\"/" "$work/scene.json" >"$work/control.json"
  rm -f "$work/control.png"
  "$bin" render "$work/control.json" -o "$work/control.png" --backend cpu --quiet 2>"$work/err"
  local got=$? why=ok
  [[ $got == 0 && -s $work/control.png ]] || why="exit status $got: $(head -c 300 "$work/err")"
  check "$1" "$why"
}
expect_renders "glTF with a buffer file" good_buffer.gltf
# The control: an OBJ whose library is well formed renders.
mv "$work/good_mtl.obj_" "$work/good_mtl.obj"
expect_renders "obj with a well-formed material library" good_mtl.obj

# compare's inputs: any channel count and layout it can read gives a verdict; what it
# cannot is refused by name. oiiotool (openimageio-tools) makes them.
make() { oiiotool --pattern "$2" 32x24 "$3" -d float "${@:4}" -o "$work/$1" 2>"$work/err" || echo "oiiotool: $(cat "$work/err")"; }
make c1.exr "fill:color=0.25" 1
make c2.exr "fill:color=0.25,0.5" 2
make c4.png "fill:color=0.25,0.5,0.75,1" 4
make c5.exr "fill:color=0.1,0.2,0.3,0.4,0.5" 5
make c70.exr "constant:color=0.5" 70
make tiled.exr "fill:color=0.25,0.5,0.75" 3 --tile 16 16
make flat.exr "fill:color=0.25,0.5,0.75" 3
oiiotool "$work/flat.exr" "$work/c1.exr" --siappend -o "$work/parts.exr" 2>"$work/err" || echo "oiiotool: $(cat "$work/err")"
for a in c1.exr c2.exr c4.png c5.exr c70.exr tiled.exr parts.exr; do
  for b in "$a" flat.exr; do
    limit timeout 30 "$bin" compare "$work/$a" "$work/$b" --diff "$work/heat.png" >"$work/out" 2>"$work/err"
    got=$? why=ok
    ((got > 128)) && why="killed by signal $((got - 128))"
    ((got == 0 || got == 1 || got == 2)) || why="$why; exit status $got"
    ((got != 2)) || grep -q "$a\|$b" "$work/err" || why="$why; a refusal without the file's name: $(head -c 200 "$work/err")"
    [[ $a != "$b" || $got == 0 ]] || why="$why; $a against itself: exit $got: $(tail -2 "$work/out") $(head -c 200 "$work/err")"
    check "compare $a $b" "$why"
  done
done
finish
