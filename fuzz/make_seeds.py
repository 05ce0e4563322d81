#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the reader fuzzers' seed corpora under fuzz/corpus/<target>/: small valid meshes
in every encoding (generated here) plus the project's own small golden and bad inputs; also
point-cloud PLYs and model.json files. Only the folders of the targets below are replaced.
Usage: fuzz/make_seeds.py [path/to/shared]   (default: the shared folder, silk_export.paths)"""

import base64
import json
import pathlib
import shutil
import struct
import sys

repo = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(repo / "export"))  # this checkout's silk_export
from silk_export.paths import shared_dir  # noqa: E402  (the one shared-folder rule)

shared = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else shared_dir(required=True)
out = repo / "fuzz" / "corpus"

CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_Q = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
CUBE_T = [t for q in CUBE_Q for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def put(target, name, data):
    d = out / target
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def copy(target, src):
    if src.exists() and src.stat().st_size < 100_000:
        put(target, src.name, src.read_bytes())


def ply(fmt):
    e = "<" if fmt == "binary_little_endian" else ">"
    head = (
        f"ply\nformat {fmt} 1.0\ncomment seed\nelement vertex 8\nproperty float x\nproperty float y\n"
        "property float z\nproperty uchar red\nelement face 6\nproperty list uchar int vertex_indices\n"
        "element edge 1\nproperty int v1\nproperty int v2\nend_header\n"
    )
    if fmt == "ascii":
        body = "".join(f"{x} {y} {z} 7\n" for x, y, z in CUBE_V)
        body += "".join("4 " + " ".join(map(str, q)) + "\n" for q in CUBE_Q) + "0 1\n"
        return (head + body).encode()
    body = b"".join(struct.pack(e + "fffB", *v, 7) for v in CUBE_V)
    body += b"".join(struct.pack(e + "B4i", 4, *q) for q in CUBE_Q) + struct.pack(e + "ii", 0, 1)
    return head.encode() + body


def ply_points(fmt, normals=True, faces=False, double=False):
    """A PLY point cloud (the cube's corners, outward normals), optionally with the cube's faces."""
    e = "<" if fmt == "binary_little_endian" else ">"
    t = "double" if double else "float"
    props = ["x", "y", "z"] + (["nx", "ny", "nz"] if normals else [])
    head = f"ply\nformat {fmt} 1.0\nelement vertex 8\n" + "".join(f"property {t} {p}\n" for p in props)
    if faces:
        head += "element face 6\nproperty list uchar int vertex_indices\n"
    head += "end_header\n"
    rows = [list(v) + ([c - 0.5 for c in v] if normals else []) for v in CUBE_V]
    if fmt == "ascii":
        body = "".join(" ".join(repr(float(x)) for x in r) + "\n" for r in rows)
        if faces:
            body += "".join("4 " + " ".join(map(str, q)) + "\n" for q in CUBE_Q)
        return (head + body).encode()
    code = "d" if double else "f"
    body = b"".join(struct.pack(e + code * len(r), *r) for r in rows)
    if faces:
        body += b"".join(struct.pack(e + "B4i", 4, *q) for q in CUBE_Q)
    return head.encode() + body


def stl_binary(header):
    h = header.ljust(80, b" ")[:80] + struct.pack("<I", len(CUBE_T))
    return h + b"".join(
        struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *CUBE_V[i]) for i in t) + b"\0\0" for t in CUBE_T
    )


def stl_ascii():
    s = "solid cube\n"
    for t in CUBE_T:
        s += " facet normal 0 0 1\n  outer loop\n"
        s += "".join(f"   vertex {x} {y} {z}\n" for x, y, z in (CUBE_V[i] for i in t))
        s += "  endloop\n endfacet\n"
    return s + "endsolid cube\n"


def gltf_parts():
    pos = b"".join(struct.pack("<3f", *v) for v in CUBE_V)
    idx = b"".join(struct.pack("<H", i) for t in CUBE_T for i in t)
    buf = pos + idx
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"translation": [1, 2, 3], "rotation": [0, 0.7071068, 0, 0.7071068], "scale": [2, 2, 2], "children": [1]},
            {"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 5, 0, 1]},
        ],
        "meshes": [
            {
                "primitives": [
                    {"attributes": {"POSITION": 0}, "indices": 1, "mode": 4},
                    {"attributes": {"POSITION": 0}, "indices": 1, "mode": 5},
                ]
            }
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)},
        ],
        "buffers": [{"byteLength": len(buf)}],
    }
    return doc, buf


def glb(doc, buf):
    j = json.dumps(doc, allow_nan=False).encode()
    j += b" " * (-len(j) % 4)
    buf += b"\0" * (-len(buf) % 4)
    total = 12 + 8 + len(j) + 8 + len(buf)
    return (
        b"glTF"
        + struct.pack("<II", 2, total)
        + struct.pack("<I", len(j))
        + b"JSON"
        + j
        + struct.pack("<I", len(buf))
        + b"BIN\0"
        + buf
    )


OWNED = (
    "obj_reader_fuzzer",
    "ply_reader_fuzzer",
    "ply_point_cloud_fuzzer",
    "stl_reader_fuzzer",
    "off_reader_fuzzer",
    "gltf_reader_fuzzer",
    "glb_reader_fuzzer",
    "model_config_fuzzer",
    "xyz_reader_fuzzer",
)


def main():
    for target in OWNED:  # the token/grammar/pmd corpora are made elsewhere and keep regressions
        if (out / target).exists():
            shutil.rmtree(out / target)
    # OBJ
    put(
        "obj_reader_fuzzer",
        "forms.obj",
        "# all face forms\nv 0 0 0\nv 1 0 0 1\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
        "o a\ng b\nusemtl m\ns 1\nf 1/1/1 2/1/1 3/1/1\nf -4//1 -2//1 -1//1\nf 1/1 2/1 3/1 4/1\nl 1 2\n",
    )
    for g in ("cube", "octahedron", "nonmanifold_book", "dirty_cube"):
        copy("obj_reader_fuzzer", shared / "spec/golden" / f"{g}.obj")
    for b in ("empty.obj", "nan_coords.obj", "index_out_of_range.obj", "degenerate_only.obj", "garbage_bytes.obj"):
        copy("obj_reader_fuzzer", shared / "corpus/bad" / b)
    # PLY
    for fmt in ("ascii", "binary_little_endian", "binary_big_endian"):
        put("ply_reader_fuzzer", f"cube_{fmt}.ply", ply(fmt))
    copy("ply_reader_fuzzer", shared / "corpus/bad/truncated_body.ply")
    # PLY point clouds (silkgen's input): with/without normals, float/double, with faces
    put("ply_point_cloud_fuzzer", "points_normals_ascii.ply", ply_points("ascii"))
    put("ply_point_cloud_fuzzer", "points_normals_le.ply", ply_points("binary_little_endian"))
    put("ply_point_cloud_fuzzer", "points_normals_be_double.ply", ply_points("binary_big_endian", double=True))
    put("ply_point_cloud_fuzzer", "points_only_ascii.ply", ply_points("ascii", normals=False))
    put("ply_point_cloud_fuzzer", "cube_with_normals.ply", ply_points("binary_little_endian", faces=True))
    # XYZ/PTS point clouds: plain, with normals, PTS count line, commas + CRLF + comments
    put("xyz_reader_fuzzer", "points.xyz", "".join(f"{x} {y} {z}\n" for x, y, z in CUBE_V))
    put(
        "xyz_reader_fuzzer",
        "points_normals.xyz",
        "".join(
            f"{x} {y} {z} {x - 0.5:.4f} {y - 0.5:.4f} {z - 0.5:.4f}\n".replace("-0.5000", "-0.57735").replace(
                "0.5000", "0.57735"
            )
            for x, y, z in CUBE_V
        ),
    )
    put("xyz_reader_fuzzer", "points_count.pts", "8\n" + "".join(f"{x} {y} {z}\n" for x, y, z in CUBE_V))
    put(
        "xyz_reader_fuzzer",
        "points_commas_crlf.xyz",
        "# cube corners\r\n" + "".join(f"{x},{y},{z}\r\n" for x, y, z in CUBE_V),
    )
    # model.json sidecars (docs/model_contract.md)
    copy("model_config_fuzzer", repo / "tests/models/tiny/model.json")
    meta = json.loads((repo / "tests/models/tiny/model.json").read_text())
    meta.pop("versions", None)
    meta.pop("training", None)
    put("model_config_fuzzer", "minimal.json", json.dumps(meta, separators=(",", ":"), allow_nan=False))
    meta["files"]["decoder_int8"] = "decoder.int8.onnx"
    meta["dims"]["head_dim"] = 12
    put("model_config_fuzzer", "bad_head_dim.json", json.dumps(meta, allow_nan=False))
    # STL
    put("stl_reader_fuzzer", "cube_ascii.stl", stl_ascii())
    put("stl_reader_fuzzer", "cube_binary.stl", stl_binary(b"binary seed"))
    put("stl_reader_fuzzer", "cube_binary_solid_header.stl", stl_binary(b"solid but binary"))
    # OFF
    off = "OFF\n# cube\n8 6 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in CUBE_V)
    off += "".join("4 " + " ".join(map(str, q)) + "\n" for q in CUBE_Q)
    put("off_reader_fuzzer", "cube.off", off)
    put("off_reader_fuzzer", "tri_inline_counts.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n")
    # glTF / GLB
    doc, buf = gltf_parts()
    emb = json.loads(json.dumps(doc))
    emb["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(buf).decode()
    put("gltf_reader_fuzzer", "cube_embedded.gltf", json.dumps(emb, indent=1, allow_nan=False))
    cyc = json.loads(json.dumps(emb))
    cyc["nodes"][1]["children"] = [0]
    put("gltf_reader_fuzzer", "cube_cycle.gltf", json.dumps(cyc, allow_nan=False))
    put("glb_reader_fuzzer", "cube.glb", glb(doc, buf))
    copy("glb_reader_fuzzer", shared / "corpus/bad/cube_obj_text.glb")
    total = sum(f.stat().st_size for f in out.rglob("*") if f.is_file())
    print(f"wrote seeds under {out} ({total} bytes)")


main()
