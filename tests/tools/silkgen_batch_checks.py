#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""End-to-end checks of `silkgen --batch` with the committed tiny model and a small id cap, run by
ctest (tests/cli/silkgen_batch.cmake). Each mode builds its own list in a temporary folder.

  shards  SILKGEN REPO SHARED   shards 0/2 + 1/2 take every input of the sorted list exactly once
                                and their outputs are byte-identical to a 1/1 run's; with Slurm's
                                array variables instead of --shard the same split (report says
                                which applied); each output equals a single silkgen run of that file
                                and passes ../shared/tools/mesh_check.py
  resume  SILKGEN REPO SHARED   broken files (../shared/corpus/bad) are `failed` with libsilk's
                                message in the report and on stderr, the others `ok`, exit 1; a rerun
                                skips the finished ones (appended lines), --overwrite redoes them;
                                no temporary file is left
  parallel SILKGEN REPO SHARED  --parallel 3 (several meshes as rows of one decoder call on the
                                contract v4 tiny-rows folder; one after another on the batch-1 tiny
                                folder) against --parallel 1 on a list with a broken file: the same
                                output files byte for byte, the same report rows (timings, run and
                                output folder aside), the same exit status; bad --parallel values
  options SILKGEN REPO SHARED   bad --shard values and Slurm variables, stem collisions, a mesh
                                file given as the list, conflicting options: exit status and a
                                message naming the problem, nothing generated; list syntax
                                (comments, blank lines, CRLF, relative paths) and folder listing
"""

import json
import os
import pathlib
import subprocess
import sys
import tempfile

from check_report import finish

DEV = [
    "gaia__fern_tropical_a.obj",
    "gaia__maple_a.obj",
    "gaia__mushrooms__small_red_01.obj",
    "props__helmet__rome_coolus_c.obj",
]
# Small and fast: the tiny model, 120 ids, best of 2 (so the candidate fields are exercised).
GEN = ["--max-tokens", "120", "--threads", "1", "--candidates", "2", "--seed", "11"]


def run(cmd, env=None, check=None):
    e = dict(os.environ)
    for k in [k for k in e if k.startswith("SLURM_")]:
        del e[k]
    e.update(env or {})
    p = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=300, env=e)
    if check is not None and p.returncode != check:
        raise SystemExit(f"exit {p.returncode} (expected {check}): {' '.join(map(str, cmd))}\n{p.stderr}")
    return p


def report(path):
    return [json.loads(line) for line in pathlib.Path(path).read_text().splitlines()]


def inputs(repo, shared):
    return [repo / "samples/torus_knot.obj", repo / "tests/models/golden/torus_knot_points.ply"] + [
        shared / "corpus/dev" / n for n in DEV
    ]


def write_list(path, files):
    path.write_text("".join(f"{f}\n" for f in files))
    return path


def batch(silkgen, repo, lst, out, *extra, env=None, check=None):
    return run(
        [silkgen, "--batch", lst, "-o", out, "--model", repo / "tests/models/tiny", *GEN, *extra], env=env, check=check
    )


def check_shards(silkgen, repo, shared, tmp):
    failures = []
    files = inputs(repo, shared)
    lst = write_list(tmp / "list.txt", files)
    batch(silkgen, repo, lst, tmp / "all", "--format", "obj", "--report", tmp / "all.jsonl", check=0)
    seen = []
    for i in range(2):
        batch(silkgen, repo, lst, tmp / "split", "--format", "obj", "--shard", f"{i}/2", check=0)
        lines = report(tmp / "split" / f"silkgen_batch.shard-{i}-of-2.jsonl")
        seen += [r["input"] for r in lines]
        if any(r["shard"] != f"{i}/2" or r["shard_source"] != "--shard" or r["status"] != "ok" for r in lines):
            failures.append(f"shard {i}/2: report lines {lines}")
    if sorted(seen) != sorted(str(f) for f in files) or len(seen) != len(set(seen)):
        failures.append(f"shards 0/2 + 1/2 do not cover the list once: {seen}")
    for f in files:
        name = f.stem + ".obj"
        a, b = tmp / "all" / name, tmp / "split" / name
        if not a.exists() or not b.exists() or a.read_bytes() != b.read_bytes():
            failures.append(f"{name}: sharded output differs from the 1/1 run's")
    # Slurm array variables (tasks 1..2, so MIN applies) pick the same split as --shard.
    for task in (1, 2):
        env = {"SLURM_ARRAY_TASK_ID": str(task), "SLURM_ARRAY_TASK_COUNT": "2", "SLURM_ARRAY_TASK_MIN": "1"}
        batch(silkgen, repo, lst, tmp / "slurm", "--format", "obj", env=env, check=0)
        lines = report(tmp / "slurm" / f"silkgen_batch.shard-{task - 1}-of-2.jsonl")
        want = [r["input"] for r in report(tmp / "split" / f"silkgen_batch.shard-{task - 1}-of-2.jsonl")]
        if [r["input"] for r in lines] != want or any(r["shard_source"] != "SLURM_ARRAY_TASK_ID" for r in lines):
            failures.append(f"Slurm task {task}: {[(r['input'], r['shard_source']) for r in lines]}, want {want}")
    failures += check_single_runs(silkgen, repo, shared, files, tmp)
    return failures


def check_single_runs(silkgen, repo, shared, files, tmp):
    """Each batch output is what `silkgen FILE -o OUT` gives with the same options, and is sound."""
    failures = []
    for f in files:
        single = tmp / f"single_{f.stem}.obj"
        run([silkgen, f, "-o", single, "--model", repo / "tests/models/tiny", *GEN, "-q"], check=0)
        got = tmp / "split" / (f.stem + ".obj")
        if single.read_bytes() != got.read_bytes():
            failures.append(f"{f.name}: batch output differs from a single silkgen run")
    checker = shared / "tools/mesh_check.py"
    outs = sorted((tmp / "split").glob("*.obj"))
    p = run([sys.executable, checker, *outs])
    if p.returncode != 0 or len(outs) != len(files):
        failures.append(f"mesh_check.py on {len(outs)} outputs: exit {p.returncode}\n{p.stdout[-2000:]}")
    return failures


def check_resume(silkgen, repo, shared, tmp):
    failures = []
    bad = [shared / "corpus/bad" / n for n in ("empty.obj", "truncated_body.ply", "nan_coords.obj")]
    files = inputs(repo, shared)[:4] + bad
    lst = write_list(tmp / "list.txt", files)
    out, rep = tmp / "out", tmp / "r.jsonl"
    p = batch(silkgen, repo, lst, out, "--report", rep)
    lines = report(rep)
    status = {pathlib.Path(r["input"]).name: r for r in lines}
    if p.returncode != 1:
        failures.append(f"exit {p.returncode} with broken inputs, expected 1")
    for f in bad:
        r = status.get(f.name)
        if not r or r["status"] != "failed" or f.name not in (r["error"] or "") or f.name not in p.stderr:
            failures.append(f"{f.name}: expected failed with a message naming it: {r}; stderr {p.stderr[-600:]}")
        elif (out / (f.stem + ".glb")).exists():
            failures.append(f"{f.name}: an output was written for a failed input")
    good = [f for f in files if f not in bad]
    for f in good:
        r = status.get(f.name, {})
        if (
            r.get("status") != "ok"
            or not r.get("faces")
            or not r.get("tokens")
            or r.get("error") is not None
            or not (out / (f.stem + ".glb")).read_bytes().startswith(b"glTF")
        ):
            failures.append(f"{f.name}: expected ok with an output: {r}")
    before = {f: (out / (f.stem + ".glb")).stat().st_mtime_ns for f in good}
    p2 = batch(silkgen, repo, lst, out, "--report", rep)
    again = report(rep)[len(lines) :]  # appended
    if p2.returncode != 1 or sorted(r["status"] for r in again) != sorted(
        ["skipped"] * len(good) + ["failed"] * len(bad)
    ):
        failures.append(f"rerun: exit {p2.returncode}, statuses {[r['status'] for r in again]}")
    if any((out / (f.stem + ".glb")).stat().st_mtime_ns != t for f, t in before.items()):
        failures.append("rerun rewrote a finished output")
    write_list(lst, good)
    p3 = batch(silkgen, repo, lst, out, "--report", rep, "--overwrite")
    third = report(rep)[len(lines) + len(again) :]
    if p3.returncode != 0 or [r["status"] for r in third] != ["ok"] * len(good):
        failures.append(f"--overwrite: exit {p3.returncode}, statuses {[r['status'] for r in third]}")
    if len({r["run"] for r in lines + again + third}) != 3:
        failures.append("the three runs' lines do not carry three run ids")
    leftovers = [f.name for f in out.iterdir() if ".tmp" in f.name]
    if leftovers:
        failures.append(f"temporary files left: {leftovers}")
    return failures


def expect(failures, p, rc, words, label):
    if p.returncode != rc:
        failures.append(f"{label}: exit {p.returncode}, expected {rc}; stderr: {p.stderr.strip()[-400:]}")
    for w in words:
        if w.lower() not in p.stderr.lower():
            failures.append(f"{label}: stderr lacks '{w}': {p.stderr.strip()[-400:]}")


def check_options(silkgen, repo, shared, tmp):
    failures = []
    files = inputs(repo, shared)[:3]
    lst = write_list(tmp / "list.txt", files)
    for bad in ("2/2", "3/2", "-1/2", "1/0", "a/b", "1", "0/2x", "/2"):
        p = batch(silkgen, repo, lst, tmp / "o", "--shard", bad)
        expect(failures, p, 2, ["--shard", bad], f"--shard {bad}")
    for env, word in (
        ({"SLURM_ARRAY_TASK_ID": "5", "SLURM_ARRAY_TASK_COUNT": "2"}, "SLURM_ARRAY_TASK_ID=5"),
        ({"SLURM_ARRAY_TASK_ID": "0"}, "SLURM_ARRAY_TASK_COUNT"),
        ({"SLURM_ARRAY_TASK_ID": "x", "SLURM_ARRAY_TASK_COUNT": "2"}, "--shard"),
    ):
        expect(failures, batch(silkgen, repo, lst, tmp / "o", env=env), 2, [word], f"env {env}")
    # --shard wins over the Slurm variables.
    p = batch(silkgen, repo, lst, tmp / "o", "--shard", "0/1", env={"SLURM_ARRAY_TASK_ID": "9"})
    expect(failures, p, 0, [], "--shard with a broken Slurm environment")
    twin = tmp / "twin"
    twin.mkdir()
    (twin / "torus_knot.ply").write_bytes((repo / "tests/models/golden/torus_knot_points.ply").read_bytes())
    clash = write_list(tmp / "clash.txt", [files[0], twin / "torus_knot.ply"])
    expect(
        failures,
        batch(silkgen, repo, clash, tmp / "c"),
        1,
        [str(files[0]), str(twin / "torus_knot.ply")],
        "stem collision",
    )
    if (tmp / "c").exists() and any((tmp / "c").glob("*.glb")):
        failures.append("stem collision: outputs written")
    expect(failures, batch(silkgen, repo, files[0], tmp / "o"), 1, ["list file"], "a mesh as the list")
    expect(failures, batch(silkgen, repo, tmp / "nolist.txt", tmp / "o"), 1, ["nolist.txt"], "missing list")
    expect(failures, batch(silkgen, repo, lst, tmp / "o", "--tokens", tmp / "t.txt"), 2, ["--tokens"], "--tokens")
    expect(failures, run([silkgen, files[0], "-o", tmp / "x.obj", "--shard", "0/2"]), 2, ["--batch"], "--shard alone")
    failures += check_list_syntax(silkgen, repo, shared, tmp)
    return failures


def check_list_syntax(silkgen, repo, shared, tmp):
    failures = []
    sub = tmp / "lists"
    sub.mkdir()
    dev = shared / "corpus/dev"
    rel = os.path.relpath(dev / DEV[0], sub)
    text = f"# meshes\r\n\r\n{rel}\r\n  {dev / DEV[1]}  \r\n{rel}\r\n"  # the repeated line counts once
    (sub / "l.txt").write_bytes(text.encode())
    p = run([silkgen, "--batch", sub / "l.txt", "-o", tmp / "ls", "--model", repo / "tests/models/tiny", *GEN])
    got = sorted(pathlib.Path(r["input"]).name for r in report(tmp / "ls/silkgen_batch.jsonl"))
    if p.returncode != 0 or got != sorted(DEV[:2]):
        failures.append(f"list syntax: exit {p.returncode}, inputs {got}; {p.stderr[-400:]}")
    folder = tmp / "folder"
    folder.mkdir()
    for f in inputs(repo, shared)[:3]:
        (folder / f.name).write_bytes(f.read_bytes())
    (folder / "notes.txt").write_text("not a mesh\n")
    (folder / "deeper").mkdir()
    (folder / "deeper" / "x.obj").write_bytes((dev / DEV[0]).read_bytes())
    p = run([silkgen, "--batch", folder, "-o", tmp / "fo", "--model", repo / "tests/models/tiny", *GEN])
    got = [r["entry"] for r in report(tmp / "fo/silkgen_batch.jsonl")]
    if p.returncode != 0 or got != sorted(f.name for f in inputs(repo, shared)[:3]):
        failures.append(f"folder: exit {p.returncode}, entries {got} (sorted, no subfolders, no .txt)")
    expect(
        failures,
        run([silkgen, "--batch", folder, "-o", folder, "--model", repo / "tests/models/tiny"]),
        1,
        ["input folder"],
        "OUTDIR = input folder",
    )
    return failures


def without_times(path):
    """The report's rows without what differs between two runs: times, the run id, the output folder."""
    rows = report(path)
    for r in rows:
        for k in ("seconds", "time", "run"):
            r.pop(k, None)
        r["output"] = pathlib.Path(r["output"]).name if r["output"] else r["output"]
    return rows


def check_parallel(silkgen, repo, shared, tmp):
    failures = []
    files = inputs(repo, shared)[:3] + [shared / "corpus/bad/assimp_invalid.off"] + inputs(repo, shared)[3:5]
    lst = write_list(tmp / "list.txt", files)
    for model in ("tiny-rows", "tiny"):
        outs = {}
        for parallel in ("1", "3"):
            out = tmp / f"{model}_p{parallel}"
            cmd = [silkgen, "--batch", lst, "-o", out, "--model", repo / "tests/models" / model, *GEN]
            p = run([*cmd, "--candidates", "3", "--parallel", parallel])
            outs[parallel] = (out, p.returncode, p.stderr)
        (o1, rc1, err1), (o3, rc3, err3) = outs["1"], outs["3"]
        label = f"{model} --parallel 3"
        if (rc1, rc3) != (1, 1):
            failures.append(f"{label}: exit {rc3}, --parallel 1 exit {rc1} (both 1: one input is broken)\n{err3}")
        meshes1 = sorted(f.name for f in o1.iterdir() if f.suffix == ".glb")
        meshes3 = sorted(f.name for f in o3.iterdir() if f.suffix == ".glb")
        if meshes1 != meshes3 or len(meshes1) != len(files) - 1:
            failures.append(f"{label}: outputs {meshes3}, --parallel 1 wrote {meshes1}")
        for name in set(meshes1) & set(meshes3):
            if (o1 / name).read_bytes() != (o3 / name).read_bytes():
                failures.append(f"{label}: {name} differs from --parallel 1's")
        r1, r3 = without_times(o1 / "silkgen_batch.jsonl"), without_times(o3 / "silkgen_batch.jsonl")
        if r1 != r3:
            failures.append(f"{label}: report rows differ from --parallel 1's:\n{r3}\n{r1}")
        if [r["status"] for r in r3].count("failed") != 1 or len(r3) != len(files):
            failures.append(f"{label}: report statuses {[r['status'] for r in r3]} (one failed of {len(files)})")
        if "assimp_invalid.off" not in err3 or err1.count("silkgen: [") != err3.count("silkgen: ["):
            failures.append(f"{label}: stderr lines differ from --parallel 1's\n{err3}\n{err1}")
    bad = [silkgen, "--batch", lst, "-o", tmp / "bad", "--model", repo / "tests/models/tiny-rows", *GEN]
    for value in ("0", "17", "x"):
        expect(failures, run([*bad, "--parallel", value]), 2, ["--parallel"], f"--parallel {value}")
    expect(failures, run([*bad, "--parallel", "17"]), 2, ["[1, 16]"], "--parallel 17: the range")
    single = [silkgen, repo / "samples/torus_knot.obj", "-o", tmp / "one.obj", "--model", repo / "tests/models/tiny"]
    expect(failures, run([*single, "--parallel", "2"]), 2, ["--parallel is a --batch option"], "no --batch")
    return failures


def main():
    mode, silkgen, repo, shared = sys.argv[1], *(pathlib.Path(a).resolve() for a in sys.argv[2:5])
    checks = {"shards": check_shards, "resume": check_resume, "options": check_options, "parallel": check_parallel}
    if mode not in checks:
        print(__doc__)
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        failures = checks[mode](silkgen, repo, shared, pathlib.Path(tmp))
    return finish(f"silkgen --batch {mode}", failures)


if __name__ == "__main__":
    sys.exit(main())
