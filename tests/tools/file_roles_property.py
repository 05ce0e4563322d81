#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Property test of "Silk never writes to a file it reads" (apps/common/file_roles.h): generated
argument combinations of silkgen (single and --batch) and silktok (encode, decode, repair) whose
outputs, --tokens/--stats files and reports point at the inputs, the list and the report through
every spelling of them: the same path, "./", "sub/..", an absolute path, a symlink, a hard link and
a case variant. After each run none of the files that run reads (its inputs, its list) changed
(SHA-256 and mtime), and its report only grew by whole JSON lines; no run crashed (exit 0, 1, 2).
A file the run does not read may be written (the user named it as an output). Prints the number
of combinations.

  file_roles_property.py SILKGEN SILKTOK REPO [--all]   (default: a fixed-seed sample of 160)
"""

import hashlib
import itertools
import json
import os
import pathlib
import random
import subprocess
import sys
import tempfile
import time

from check_report import finish

GEN = ["--max-tokens", "40", "--threads", "1", "--candidates", "1", "--seed", "5", "-q"]


def fingerprint(path):
    return hashlib.sha256(path.read_bytes()).hexdigest(), os.stat(path).st_mtime_ns


def aliases(tmp, name):
    """Spellings of tmp/name, run from cwd=tmp: they all open the same file (the case variant
    only on a case-insensitive file system; elsewhere it names a new file)."""
    stem, ext = os.path.splitext(name)
    sym, hard = f"sym_{stem}{ext}", f"hard_{stem}{ext}"
    if not (tmp / sym).exists():
        os.symlink(tmp / name, tmp / sym)
        os.link(tmp / name, tmp / hard)
    return [name, f"./{name}", f"sub/../{name}", str(tmp / name), sym, hard, stem.upper() + ext.upper()]


def setup(tmp, repo):
    (tmp / "sub").mkdir()
    (tmp / "out").mkdir()
    (tmp / "in.obj").write_bytes((repo / "samples/torus_knot.obj").read_bytes())
    (tmp / "t.tokens.txt").write_text("".join(f"{i}\n" for i in (10266, 5, 17, 40)))
    (tmp / "list.txt").write_text("in.obj\n")
    (tmp / "list2.txt").write_text("in.obj\nhard_in.obj\n")
    (tmp / "list3.txt").write_text("sym_in.obj\n")
    (tmp / "r.jsonl").write_text('{"earlier": "line"}\n')
    table = {n: aliases(tmp, n) for n in ("in.obj", "t.tokens.txt", "list.txt", "r.jsonl")}
    return table


def combinations(table):
    """(tool, arguments, the files the run reads, its report or None)."""
    targets = [a for spellings in table.values() for a in spellings]
    for opt, t in itertools.product(("-o", "--tokens", "--stats"), targets):
        yield "silkgen", ["in.obj", opt, t] + (["-o", "fresh.glb"] if opt != "-o" else []), ["in.obj"], None
    lists = ("list.txt", "list2.txt", "list3.txt")
    for lst, outdir, fmt, overwrite, rep in itertools.product(
        lists, (".", "out", "sub/.."), ("obj", "glb"), (False, True), targets + [None]
    ):
        args = ["--batch", lst, "-o", outdir, "--format", fmt] + (["--overwrite"] if overwrite else [])
        report = rep or f"{outdir}/silkgen_batch.jsonl"
        yield "silkgen", args + (["--report", rep] if rep else []), [lst, "in.obj"], report
    for (cmd, src), t in itertools.product(
        (("encode", "in.obj"), ("decode", "t.tokens.txt"), ("repair", "t.tokens.txt")), targets
    ):
        yield "silktok", [cmd, src, "-o", t], [src], None


def check_run(tmp, label, p, reads, before, report, report_before):
    """The failures of one run: a crash, a file it reads changed, its report rewritten."""
    failures = []
    if p.returncode not in (0, 1, 2):
        failures.append(f"{label}: exit {p.returncode}: {p.stderr.decode(errors='replace')[-300:]}")
    for f in reads:
        if fingerprint(f) != before[f]:
            failures.append(f"{label}: {f.name}, which it reads, was modified")
    if report is not None and (tmp / report).is_file():
        now = (tmp / report).read_bytes()
        if not now.startswith(report_before):
            failures.append(f"{label}: the report {report} was rewritten, not appended to")
        else:
            try:
                [json.loads(line) for line in now[len(report_before) :].decode().splitlines()]
            except (ValueError, UnicodeDecodeError):
                failures.append(f"{label}: the report {report} grew by something other than JSON lines")
    return failures


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    silkgen, silktok, repo = (pathlib.Path(a).resolve() for a in sys.argv[1:4])
    failures = []
    t0 = time.monotonic()
    with tempfile.TemporaryDirectory() as d:
        tmp = pathlib.Path(d)
        table = setup(tmp, repo)
        combos = list(combinations(table))
        total = len(combos)
        if "--all" not in sys.argv:
            combos = random.Random(35).sample(combos, min(160, total))
        pristine = {
            n: (tmp / n).read_bytes()
            for n in ("in.obj", "t.tokens.txt", "list.txt", "list2.txt", "list3.txt", "r.jsonl")
        }
        for tool, args, read_names, report in combos:
            for n, data in pristine.items():  # every run starts from the same files (hard links kept)
                if (tmp / n).read_bytes() != data:
                    (tmp / n).write_bytes(data)
            reads = [tmp / n for n in read_names]
            before = {f: fingerprint(f) for f in reads}
            report_path = tmp / report if report else None
            report_before = report_path.read_bytes() if report_path and report_path.is_file() else b""
            exe = silkgen if tool == "silkgen" else silktok
            extra = ["--model", str(repo / "tests/models/tiny"), *GEN] if tool == "silkgen" else []
            p = subprocess.run([str(exe), *args, *extra], cwd=tmp, capture_output=True, timeout=60)
            failures += check_run(tmp, f"{tool} {' '.join(args)}", p, reads, before, report, report_before)
    print(
        f"file_roles_property: {len(combos)} argument combinations run (of {total} generated), "
        f"{time.monotonic() - t0:.1f} s"
    )
    return finish("file roles property", failures)


if __name__ == "__main__":
    sys.exit(main())
