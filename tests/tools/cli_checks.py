#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""End-to-end checks of the silktok binary, run by ctest (tests/cli/silktok.cmake).

bad SILKTOK SHARED      every corpus/bad file through `encode` and `stats`: non-zero exit,
                        stderr names the file, no output file left, each within seconds
golden SILKTOK SHARED   `encode` of the 14 goldens and (batch form, -j 2) of the 160 dev meshes:
                        token files byte-identical to the official ones, official refusals refused
roundtrip SILKTOK SHARED  `roundtrip --json` on the 14 goldens: exact
decode SILKTOK SHARED   `decode` of the 140 golden-dev streams, faithful and with
                        --split-nonmanifold-vertices, judged by shared/tools/mesh_check.py: the
                        split OBJ has no vertex with two fans and the same faces; some faithful
                        ones do have such vertices (the references contain them)
"""

import csv
import gzip
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

from check_report import finish

# A hang guard, not a speed target (those live in bench/): each bad file must be refused within
# this many seconds; the sanitizer build raises it (tests/cli/silktok.cmake).
TIME_LIMIT_S = int(os.environ.get("SILK_HANG_GUARD_S", "20"))


def run(cmd, timeout=TIME_LIMIT_S * 10):
    t0 = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout)
    return p, time.monotonic() - t0


def check_bad(silktok, shared):
    bad_dir = pathlib.Path(shared) / "corpus" / "bad"
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        cases = []
        for f in sorted(bad_dir.iterdir()):
            if f.name in ("README.md", "IndexOutOfRange.bin"):
                continue
            if f.suffix == ".gz":  # the README says: decompress first
                out = tmp / f.stem
                with gzip.open(f, "rb") as src, open(out, "wb") as dst:
                    shutil.copyfileobj(src, dst)
                cases.append(out)
            else:
                cases.append(f)
        for case in cases:
            for sub in ("encode", "stats"):
                out = tmp / (case.name + "." + sub + ".out.txt")
                cmd = [silktok, sub, str(case)] + (["-o", str(out)] if sub == "encode" else [])
                try:
                    p, dt = run(cmd, timeout=TIME_LIMIT_S)
                except subprocess.TimeoutExpired:
                    failures.append(f"{case.name} {sub}: timed out after {TIME_LIMIT_S}s")
                    continue
                why = []
                if p.returncode == 0:
                    why.append("exit code 0")
                if p.returncode < 0 or p.returncode >= 128:
                    why.append(f"crashed (exit {p.returncode})")
                if case.name not in p.stderr:
                    why.append("stderr does not name the file")
                if "AddressSanitizer" in p.stderr or "runtime error" in p.stderr:
                    why.append("sanitizer report")
                if out.exists() or list(tmp.glob(out.name + "*")):
                    why.append("output file left behind")
                msg = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "(no message)"
                print(f"{case.name:32s} {sub:6s} exit {p.returncode} {dt:6.2f}s  {msg}")
                if why:
                    failures.append(f"{case.name} {sub}: " + ", ".join(why))
    return failures


def check_golden(silktok, shared):
    shared = pathlib.Path(shared)
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for tok in sorted((shared / "spec" / "golden").glob("*.tokens.txt")):
            name = tok.name[: -len(".tokens.txt")]
            out = tmp / (name + ".txt")
            p, _ = run([silktok, "encode", str(shared / "spec" / "golden" / (name + ".obj")), "-o", str(out)])
            if p.returncode != 0 or not out.exists() or out.read_bytes() != tok.read_bytes():
                failures.append(f"golden {name}: tokens differ ({p.stderr.strip()})")
        rows = list(csv.DictReader(open(shared / "spec" / "golden-dev" / "INDEX.tsv"), delimiter="\t"))
        inputs = [str(shared / "corpus" / "dev" / (r["name"] + ".obj")) for r in rows]
        outdir = tmp / "dev"
        p, dt = run([silktok, "encode", *inputs, "-o", str(outdir), "-j", "2"], timeout=600)
        same = refused = 0
        for r in rows:
            out = outdir / (r["name"] + ".tokens.txt")
            if r["status"] == "ok":
                ref = shared / "spec" / "golden-dev" / (r["name"] + ".tokens.txt")
                if out.exists() and out.read_bytes() == ref.read_bytes():
                    same += 1
                else:
                    failures.append(f"dev {r['name']}: tokens differ from the official ones")
            else:
                if out.exists():
                    failures.append(f"dev {r['name']}: official code refuses it ({r['message']}) but we wrote tokens")
                elif r["name"] in p.stderr:
                    refused += 1
                else:
                    failures.append(f"dev {r['name']}: refused without naming the file")
        print(
            f"dev corpus via `silktok encode -j 2`: {same} token files identical, {refused} refused as the "
            f"reference does, {dt:.2f}s; exit {p.returncode}"
        )
        if p.returncode == 0:
            failures.append("batch encode exited 0 although 20 inputs are refused")
    return failures


def check_roundtrip(silktok, shared):
    failures = []
    for obj in sorted((pathlib.Path(shared) / "spec" / "golden").glob("*.obj")):
        p, _ = run([silktok, "roundtrip", "--json", str(obj)])
        try:
            j = json.loads(p.stdout)
        except json.JSONDecodeError:
            failures.append(f"{obj.name}: no JSON ({p.stderr.strip()})")
            continue
        print(
            f"{obj.stem:20s} representable {j['representable_faces']:4d} recovered {j['recovered']:4d} "
            f"reversed {j['reversed']} missing {j['missing']} extra {j['extra_faces']}"
        )
        if p.returncode != 0 or not j["exact"]:
            failures.append(f"{obj.name}: roundtrip not exact")
    return failures


def check_decode(silktok, shared):
    sys.path.insert(0, str(pathlib.Path(shared) / "tools"))
    import mesh_check  # the independent checker (shares no code with Silk)

    failures, with_bowties = [], 0
    with tempfile.TemporaryDirectory() as tmp:
        for tok in sorted((pathlib.Path(shared) / "spec" / "golden-dev").glob("*.tokens.txt")):
            keep, split = pathlib.Path(tmp) / "keep.obj", pathlib.Path(tmp) / "split.obj"
            p1, _ = run([silktok, "decode", str(tok), "-o", str(keep)])
            p2, _ = run([silktok, "decode", str(tok), "-o", str(split), "--split-nonmanifold-vertices"])
            if p1.returncode or p2.returncode:
                failures.append(f"{tok.name}: decode failed ({p1.stderr.strip()} {p2.stderr.strip()})")
                continue
            a, b = (
                mesh_check.verdict(*mesh_check.read_obj(str(keep))),
                mesh_check.verdict(*mesh_check.read_obj(str(split))),
            )
            with_bowties += a["nonmanifold_vertices"] > 0
            if not b["ok"] or b["faces"] != a["faces"] or b["edge_manifold"] != a["edge_manifold"]:
                failures.append(f"{tok.name}: split output {b}, faithful {a}")
    print(
        f"decode: {with_bowties} faithful meshes with vertices of two or more fans, all split outputs vertex-manifold"
    )
    if with_bowties == 0:
        failures.append("no faithful decode had a vertex with two fans (the check would be vacuous)")
    return failures


def main():
    mode, silktok, shared = sys.argv[1:4]
    failures = {"bad": check_bad, "golden": check_golden, "roundtrip": check_roundtrip, "decode": check_decode}[mode](
        silktok, shared
    )
    sys.exit(finish(f"silktok {mode}", failures))


if __name__ == "__main__":
    main()
