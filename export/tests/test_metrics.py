# SPDX-License-Identifier: MIT
"""Evaluation on shapes with known answers: a mesh against itself, a cube against a larger
concentric cube (analytic distances), reversed orientation (NC = -1, |NC| = 1), and the
structural figures of closed, flipped, open and multi-part meshes."""

from __future__ import annotations

import json

import numpy as np
import pytest

import silk_mesh
from silk_export.cli import main
from silk_export.evaluation.metrics import compare_meshes
from silk_export.evaluation.structure import mesh_structure, surface_patches

CUBE_V = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=np.float64)
CUBE_F = np.array(
    [
        [0, 1, 3],
        [0, 3, 2],
        [4, 6, 7],
        [4, 7, 5],
        [0, 4, 5],
        [0, 5, 1],
        [2, 3, 7],
        [2, 7, 6],
        [0, 2, 6],
        [0, 6, 4],
        [1, 5, 7],
        [1, 7, 3],
    ]
)


def test_cube_is_closed_and_outward():
    s = mesh_structure(CUBE_V, CUBE_F)
    assert s == {
        "faces": 12,
        "vertices": 8,
        "components": 1,
        "manifold": True,
        "watertight": True,
        "orientation_consistent": True,
        "boundary_edges": 0,
        "nonmanifold_edges": 0,
    }
    a, b, c = CUBE_V[CUBE_F[:, 0]], CUBE_V[CUBE_F[:, 1]], CUBE_V[CUBE_F[:, 2]]
    centroids = (a + b + c) / 3
    assert (np.einsum("ij,ij->i", np.cross(b - a, c - a), centroids) > 0).all()  # outward normals


def test_structure_flags():
    flipped = CUBE_F.copy()
    flipped[0] = flipped[0, ::-1]
    assert not mesh_structure(CUBE_V, flipped)["orientation_consistent"]
    open_box = mesh_structure(CUBE_V, CUBE_F[2:])
    assert open_box["manifold"] and not open_box["watertight"] and open_box["boundary_edges"] == 4
    two = mesh_structure(np.vstack([CUBE_V, CUBE_V + 5]), np.vstack([CUBE_F, CUBE_F + 8]))
    assert two["components"] == 2 and two["faces"] == 24
    fin = mesh_structure(np.vstack([CUBE_V, [[0, 3, 3]]]), np.vstack([CUBE_F, [[0, 1, 8]]]))
    assert not fin["manifold"] and fin["nonmanifold_edges"] == 1
    # unwelded copies of positions are welded first (as in the dev corpus manifest)
    v2 = np.vstack([CUBE_V, CUBE_V])
    f2 = CUBE_F.copy()
    f2[::2] += 8
    assert mesh_structure(v2, f2)["watertight"]


def test_surface_patches_join_faces_by_edges_not_vertices():
    assert len(set(surface_patches(CUBE_F))) == 1
    two = surface_patches(np.vstack([CUBE_F, CUBE_F + 8]))
    assert len(set(two)) == 2 and len(set(two[:12])) == 1 and two[0] != two[12]
    bowtie = [[0, 1, 2], [0, 3, 4], [0, 4, 5]]  # the first shares only vertex 0 with the others
    p = surface_patches(bowtie)
    assert p[1] == p[2] != p[0]
    assert mesh_structure(np.zeros((6, 3)) + np.arange(6)[:, None], np.array(bowtie))["components"] == 1
    assert surface_patches(np.zeros((0, 3), int)) == []


def test_mesh_against_itself_is_zero():
    m = compare_meshes(CUBE_V, CUBE_F, CUBE_V, CUBE_F, n_points=2000, seed=3)
    assert m["cd"] == 0.0 and m["hd"] == 0.0 and m["nc"] == pytest.approx(1.0) and m["abs_nc"] == pytest.approx(1.0)


def test_normalisation_removes_scale_and_offset():
    m = compare_meshes(CUBE_V, CUBE_F, CUBE_V * 7 + 3, CUBE_F, n_points=2000, seed=3)
    assert m["cd"] < 1e-12 and m["hd"] < 1e-12


def test_reversed_orientation():
    m = compare_meshes(CUBE_V, CUBE_F, CUBE_V, CUBE_F[:, ::-1], n_points=4000, seed=1)
    # every nearest sample lies on the same face (normal reversed: -1) or, near an edge, on a
    # perpendicular face (0): so NC = -|NC|, close to -1
    assert m["nc"] < -0.9 and m["abs_nc"] == pytest.approx(-m["nc"]) and m["cd"] < 0.05


def test_cube_against_larger_cube_matches_analytic_distances():
    s = 1.25  # outer half-size; inner cube half-size 1, both centred
    m = compare_meshes(CUBE_V, CUBE_F, CUBE_V * s, CUBE_F, n_points=8000, seed=0, normalize=False)
    # inner -> outer: every inner surface point is exactly s - 1 from the outer surface
    # outer -> inner: on a face x = s, d = sqrt((s-1)^2 + a(y)^2 + a(z)^2), a(u) = max(|u| - 1, 0)
    u = (np.arange(4000) + 0.5) / 4000 * 2 * s - s  # midpoint rule over [-s, s]
    a = np.maximum(np.abs(u) - 1, 0)
    outer_mean = np.sqrt((s - 1) ** 2 + a[:, None] ** 2 + a[None, :] ** 2).mean()
    spacing = np.sqrt(24 * s * s / 8000)  # sample spacing: nearest-sample error bound scale
    assert m["cd_a_to_b"] == pytest.approx(s - 1, abs=0.5 * spacing)
    assert m["cd_b_to_a"] == pytest.approx(outer_mean, abs=0.5 * spacing)
    assert m["cd"] == pytest.approx(0.5 * (s - 1 + outer_mean), abs=0.5 * spacing)
    assert m["hd"] == pytest.approx(np.sqrt(3) * (s - 1), abs=spacing)  # the corners
    assert m["nc"] > 0.9  # 1 except near the edges, where the nearest sample is on another face


def test_eval_cli_on_folders(tmp_path, capsys):
    gen, ref = tmp_path / "gen", tmp_path / "ref"
    gen.mkdir()
    ref.mkdir()
    with silk_mesh.Mesh(CUBE_V, CUBE_F) as m:
        m.save(ref / "cube.obj")
        m.save(gen / "cube.obj")
    with silk_mesh.Mesh(CUBE_V, CUBE_F[:, ::-1]) as m:
        m.save(gen / "flip.obj")
        m.save(ref / "flip.obj")
    assert main(["eval", str(gen), str(ref), "--points", "1000", "--out", str(tmp_path / "e.json")]) == 0
    res = json.loads((tmp_path / "e.json").read_text())
    assert res["summary"]["evaluated"] == 2 and res["summary"]["mean_cd"] == 0.0
    assert res["summary"]["rate_watertight"] == 1.0
    assert {r["name"] for r in res["meshes"]} == {"cube", "flip"}
