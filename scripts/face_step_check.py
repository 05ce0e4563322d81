# SPDX-License-Identifier: MIT
"""Where the folds of a face-guided mesh come from (issue 33): each face the ids carry is traced
to the step that decided it, and each folded interior edge to the later of its two faces' steps.

    build/apps/silkgen IN.obj -o OUT.obj --face-guidance hard --face-tolerance 4 --trace T.json
    PYTHONPATH=bindings/python SILK_LIBRARY=build/engine/libsilk.so \\
        python3 scripts/face_step_check.py T.json [T2.json ...]
    ... python3 scripts/face_step_check.py ../shared/corpus/dev/*.obj   # reference meshes' ids

A face is decided by the last-written of its three vertices, v: with a corner in the previous
layer, by the B id of v's row that joins that column (the later one when two B ids do); with all
three corners in v's layer, by v's position (the in-layer edges were stated by S windows before
it). Each deciding B id is classed by silkgen's trace: forced by the grammar, judged by face
guidance and some legal id passed, judged and none passed (a fallback), or not judged (guidance
off). An interior edge is folded when its two faces, wound as decoded, point more than a right
angle apart (their faces make an angle under 90 deg measured inside the pair: one lies over the
other); it is charged to the later-decided face. Prints, per class, the faces, the edges charged
and the share of those folded; if guidance's passed steps still fold as often as the others, it
misjudges its faces; if their edges rarely fold, the folds come from steps it does not choose.
Also prints how many earlier rows of its layer each vertex is linked to (what makes a position
impossible to place without folding). A mesh file instead of a trace: its ids as libsilk
encodes them, every step "not judged" (reference meshes)."""

from __future__ import annotations

import json
import sys
from collections import Counter

import numpy as np

import silk_mesh

V = silk_mesh.vocab()  # the id ranges, as libsilk states them


def parse(tokens: list[int]) -> list[dict]:
    """The vertices in reading order: layer, row, the steps of their ids, their in-layer distances
    (window bits and X ids), their B ids' steps and start columns, the step that ends their layer."""
    verts: list[dict] = []
    layer, row, cur, open_layer = 0, 0, None, []
    for step, t in enumerate(tokens):
        if t in (V["c_id"], V["u_id"], V["e_id"]):
            for v in open_layer:
                v["end"] = step
            open_layer = []
            layer, row, cur = (0 if t == V["c_id"] else layer + 1), 0, None
        elif V["k_begin"] <= t < V["k_end"]:
            cur = {"layer": layer, "row": row, "k": step, "b": [], "d": []}
            verts.append(cur)
            open_layer.append(cur)
            row += 1
        elif V["o_begin"] <= t < V["o_end"]:
            cur["o"] = step
        elif V["b_begin"] <= t < V["b_end"]:
            cur["b"].append((step, (t - V["b_begin"]) // 26))  # 26 cases per start column
        elif V["s_begin"] <= t < V["s_end"]:
            cur["d"] += [d + 1 for d in range(8) if (t - V["s_begin"]) >> d & 1]  # bit d-1: distance d
        elif V["x_begin"] <= t < V["x_end"]:
            cur["d"].append(t - V["x_begin"] + 1)  # value e: distance e + 1
    return verts


def b_step(v: dict, column: int) -> int:
    """The step of the B id of v's row that joins `column`: the last one starting at or before it
    (a row's B ids start at increasing columns and each covers at most the next 5)."""
    return max((s for s, start in v["b"] if start <= column), default=v["o"])


def in_layer_edge_step(a: dict, b: dict) -> tuple[int, str]:
    """When the edge between two rows of one layer is fixed, geometry included: a forward
    statement by the earlier row once the later row has its position; a statement that wraps
    past the layer's last row only at the layer's end, when the layer's size is known."""
    first, last = (a, b) if a["row"] < b["row"] else (b, a)
    if last["row"] - first["row"] in first["d"]:
        return last["o"], "position"
    return last["end"], "layer end"


def step_class(step: dict) -> str:
    if step.get("forced"):
        return "forced"
    return {"passed": "passed", "fallback": "fallback"}.get(step.get("face", ""), "not judged")


def links(verts: list[dict]) -> Counter:
    """Vertices by how many earlier rows of their layer link to them (window bit or X id)."""
    out: Counter = Counter()
    layer: list[dict] = []
    for v in verts + [{"row": 0}]:
        if v["row"] == 0:
            for j in range(len(layer)):
                out[min(sum(1 for a in layer[:j] if j - a["row"] in a["d"]), 3)] += 1
            layer = []
        layer.append(v)
    return out


def load(path: str) -> tuple[list[int], list[dict]]:
    """A trace's ids and steps; a mesh file's ids (encoded by libsilk) with no steps."""
    if path.endswith(".json"):
        trace = json.load(open(path))
        return [t for t in trace["tokens"] if t != V["eos_id"]], trace["steps"]
    ids = silk_mesh.encode(path)
    return ids, [{} for _ in ids]


def check(path: str) -> tuple[Counter, Counter, Counter, Counter]:
    tokens, steps = load(path)
    verts = parse(tokens)
    mesh = silk_mesh.decode(tokens, grid_coordinates=True)
    pos = np.asarray(mesh.positions, float)
    faces = np.asarray(mesh.triangles, int)
    if len(pos) != len(verts):
        raise SystemExit(f"{path}: {len(pos)} decoded vertices for {len(verts)} vertices in the ids")
    deciding, klass = [], []
    for f in faces:
        corners = sorted((verts[int(i)] for i in f), key=lambda v: v["o"])
        v = corners[-1]  # the last written
        step, kind = v["o"], "position " + step_class(steps[v["o"]])
        for w in corners[:-1]:
            if w["layer"] == v["layer"] - 1:
                joined = b_step(v, w["row"])
                if joined > step:
                    step, kind = joined, "B " + step_class(steps[joined])
        for x, y in ((corners[0], corners[1]), (corners[0], v), (corners[1], v)):
            if x["layer"] == y["layer"]:
                e_step, e_kind = in_layer_edge_step(x, y)
                if e_step > step:
                    step, kind = e_step, "layer end (wrapped window)"
        deciding.append(step)
        klass.append(kind + (" [in-layer face]" if corners[0]["layer"] == v["layer"] else ""))
    a, b, c = pos[faces[:, 0]], pos[faces[:, 1]], pos[faces[:, 2]]
    normal = np.cross(b - a, c - a)
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-12)
    on_edge: dict = {}
    for i, f in enumerate(faces):
        for k in range(3):
            on_edge.setdefault(tuple(sorted((int(f[k]), int(f[(k + 1) % 3])))), []).append(i)
    face_count, edges, folded = Counter(klass), Counter(), Counter()
    for pair in on_edge.values():
        if len(pair) != 2:
            continue
        x, y = pair
        later = klass[x] if deciding[x] >= deciding[y] else klass[y]
        edges[later] += 1
        folded[later] += int(np.dot(normal[x], normal[y]) < 0)
    return face_count, edges, folded, links(verts)


def main(paths: list[str]) -> None:
    faces, edges, folded, linked = Counter(), Counter(), Counter(), Counter()
    meshes = 0
    for p in paths:
        try:
            f, e, d, k = check(p)
        except silk_mesh.SilkError as err:  # a reference mesh libsilk refuses to encode
            print(f"{p}: skipped ({err})")
            continue
        meshes += 1
        faces += f
        edges += e
        folded += d
        linked += k
    total_f, total_e = sum(faces.values()), sum(edges.values())
    print(
        f"{meshes} mesh(es), {total_f} faces, {total_e} interior edges, "
        f"{sum(folded.values()) / max(total_e, 1):.1%} folded (normals > 90 deg apart)"
    )
    print("| deciding step | faces | share of faces | edges charged | folded |")
    print("|---|---|---|---|---|")
    for k in sorted(faces, key=lambda k: -faces[k]):
        print(f"| {k} | {faces[k]} | {faces[k] / total_f:.1%} | {edges[k]} | {folded[k] / max(edges[k], 1):.1%} |")
    total_v = sum(linked.values())
    print(
        "vertices by earlier rows of their layer linked to them: "
        + ", ".join(f"{k}{'+' if k == 3 else ''}: {linked[k] / max(total_v, 1):.1%}" for k in range(4))
    )


if __name__ == "__main__":
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    main(sys.argv[1:])
