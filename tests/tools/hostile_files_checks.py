#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Issue 35's reproductions against silkgen and silktok, each a check that failed on 35a6440: files
destroyed by `silkgen --batch`, reads that block or never end, writes that fail silently. Each case
runs in its own temporary folder with the committed tiny model and a small id cap, and asserts the
exit status, the message (naming the file and the problem), that no input/list/report changed, the
time (under 10 s) and, where the old code ran away, the peak memory (under 512 MB; ru_maxrss).

  batch   SILKGEN SILKTOK REPO   items 1-6: inputs in OUTDIR, NUL/control/over-long list lines,
                                 --report naming an input or the list, an unwritable report, hidden
                                 temporaries and 245-256-byte output names, --shard "" and bad
                                 SLURM_* values
  files   SILKGEN SILKTOK REPO   items 8-9: a FIFO in the list and as the list (under `timeout 15`),
                                 a symlink to /dev/zero, a 64 MB one-line list; outputs that are
                                 inputs for single silkgen and silktok runs; the error-line format
  signals SILKGEN SILKTOK REPO   SIGTERM/SIGINT end a batch within a second (exit 143/130), leaving
                                 no temporary; a second signal ends it at once, no temporary left
"""

import hashlib
import json
import os
import pathlib
import resource
import signal
import subprocess
import sys
import tempfile
import time

from check_report import finish

GEN = ["--max-tokens", "60", "--threads", "1", "--candidates", "1", "--seed", "3", "-q"]
MB = 1024 * 1024


class Ctx:
    def __init__(self, silkgen, silktok, repo, tmp):
        self.silkgen, self.silktok, self.repo, self.tmp = silkgen, silktok, repo, tmp
        self.mesh = repo / "samples/torus_knot.obj"
        self.model = repo / "tests/models/tiny"
        self.failures = []

    def run(self, cmd, env=None, timeout=60, preexec=None):
        """Runs cmd; returns (returncode, stderr, seconds, peak RSS in MB) from wait4."""
        e = {k: v for k, v in os.environ.items() if not k.startswith("SLURM_")}
        e.update(env or {})
        t0 = time.monotonic()
        p = subprocess.Popen(
            [str(c) for c in cmd],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            env=e,
            preexec_fn=preexec,
            start_new_session=True,
        )
        try:
            _, err = p.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)  # `timeout`'s child too (the old code ignored its SIGTERM)
            _, err = p.communicate()
            self.failures.append(f"{cmd[:3]}: still running after {timeout} s (killed)")
        return p.returncode, err.decode("utf-8", "replace"), time.monotonic() - t0

    def rss(self, cmd, env=None, timeout=60):
        """(returncode, stderr, seconds, peak MB) through os.wait4, the child's own ru_maxrss."""
        e = {k: v for k, v in os.environ.items() if not k.startswith("SLURM_")}
        e.update(env or {})
        t0 = time.monotonic()
        p = subprocess.Popen(
            [str(c) for c in cmd], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=e, start_new_session=True
        )
        deadline = t0 + timeout
        err = b""
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() > deadline:
                os.killpg(p.pid, signal.SIGKILL)
                deadline = float("inf")
                self.failures.append(f"{cmd[:3]}: still running after {timeout} s (killed)")
            time.sleep(0.02)
        err = p.stderr.read()
        p.returncode = os.waitstatus_to_exitcode(status)
        return p.returncode, err.decode("utf-8", "replace"), time.monotonic() - t0, ru.ru_maxrss / 1024

    def expect(self, label, got, rc, words=(), seconds=10.0):
        code, err, secs = got[0], got[1], got[2]
        if code != rc:
            self.failures.append(f"{label}: exit {code}, expected {rc}; stderr: {err.strip()[-500:]}")
        for w in words:
            if w.lower() not in err.lower():
                self.failures.append(f"{label}: stderr lacks '{w}': {err.strip()[-500:]}")
        if secs > seconds:
            self.failures.append(f"{label}: took {secs:.1f} s (limit {seconds} s)")
        print(
            f"{label}: exit {code}, {secs:.2f} s{f', {got[3]:.0f} MB' if len(got) > 3 else ''}: "
            f"{err.strip().splitlines()[-1] if err.strip() else ''}"[:400]
        )

    def batch(self, lst, out, *extra, env=None):
        return self.run([self.silkgen, "--batch", lst, "-o", out, "--model", self.model, *GEN, *extra], env=env)


def fingerprint(paths):
    return {str(p): (hashlib.sha256(pathlib.Path(p).read_bytes()).hexdigest(), os.stat(p).st_mtime_ns) for p in paths}


def unchanged(ctx, label, before):
    after = fingerprint(before.keys())
    for p in before:
        if before[p] != after[p]:
            ctx.failures.append(f"{label}: {p} was modified")


def report_lines(path):
    return [json.loads(l) for l in pathlib.Path(path).read_text().splitlines()]


def case_inputs_in_outdir(ctx):
    d = ctx.tmp / "d"
    d.mkdir()
    a = d / "a.obj"
    a.write_bytes(ctx.mesh.read_bytes())
    lst = d / "list.txt"
    lst.write_text("a.obj\n")
    before = fingerprint([a, lst])
    for extra in ([], ["--overwrite"]):
        ctx.expect(
            f"1. input in OUTDIR {extra}",
            ctx.batch(lst, d, "--format", "obj", *extra),
            1,
            [str(a), "never writes to a file it reads"],
        )
    unchanged(ctx, "1. input in OUTDIR", before)
    # The same through a hard link and a symlink in another OUTDIR.
    o = ctx.tmp / "o1"
    o.mkdir()
    os.link(a, o / "a.obj")
    ctx.expect(
        "1. output is a hard link to the input",
        ctx.batch(lst, o, "--format", "obj", "--overwrite"),
        1,
        ["never writes"],
    )
    unchanged(ctx, "1. hard link", before)


def case_nul_and_control_lines(ctx):
    out = ctx.tmp / "o2"
    out.mkdir()
    rep = out / "r.glb"
    lst = ctx.tmp / "nul.txt"
    # The OS opened "<mesh>"; the stem came from the whole line ("r"): a GLB over the report.
    lst.write_bytes(str(ctx.mesh).encode() + b"\0/x/r.glb\n" + b"ctl\x1b[2Jname.obj\n" + b"x" * 5000 + b".obj\n")
    got = ctx.batch(lst, out, "--report", rep)
    ctx.expect("2. NUL, control and over-long list lines", got, 1, ["NUL byte", "control character", "longer than"])
    lines = report_lines(rep)  # still JSON lines: not overwritten by a GLB
    if sorted(r["status"] for r in lines) != ["failed"] * 3:
        ctx.failures.append(f"2. statuses {[r['status'] for r in lines]}, expected 3 failed rows")
    for r in lines:
        if not r["error"] or "list line" not in r["error"] or r["output"] is not None:
            ctx.failures.append(f"2. row without a reason naming the line: {r}")
    if any(len(l.encode()) >= 65536 for l in rep.read_text().splitlines()):
        ctx.failures.append("2. a report line of 64 KiB or more")


def case_report_is_input_or_list(ctx):
    lst = ctx.tmp / "l3.txt"
    inp = ctx.tmp / "in3.obj"
    inp.write_bytes(ctx.mesh.read_bytes())
    lst.write_text(f"{inp}\n")
    before = fingerprint([lst, inp])
    ctx.expect(
        "3. --report is an input",
        ctx.batch(lst, ctx.tmp / "o3", "--report", inp),
        1,
        ["report", str(inp), "never writes"],
    )
    ctx.expect(
        "3. --report is the list", ctx.batch(lst, ctx.tmp / "o3", "--report", lst), 1, ["report", str(lst), "the list"]
    )
    os.symlink(inp, ctx.tmp / "link3.jsonl")
    ctx.expect(
        "3. --report is a symlink to an input",
        ctx.batch(lst, ctx.tmp / "o3", "--report", ctx.tmp / "link3.jsonl"),
        1,
        ["never writes"],
    )
    unchanged(ctx, "3. report", before)


def case_report_write_fails(ctx):
    lst = ctx.tmp / "l4.txt"
    lst.write_text(f"{ctx.mesh}\n")
    ctx.expect(
        "4. --report /dev/full", ctx.batch(lst, ctx.tmp / "o4", "--report", "/dev/full"), 1, ["/dev/full", "report"]
    )
    # A regular report that cannot grow (a file size limit its earlier lines already reach; the
    # output, a few KB, still fits): the write fails, the run fails naming it.
    rep = ctx.tmp / "o4b.jsonl"
    limit = 256 * 1024
    rep.write_text('{"earlier": "' + "x" * (limit - 40) + '"}\n')

    def small_files():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    got = ctx.run(
        [ctx.silkgen, "--batch", lst, "-o", ctx.tmp / "o4b", "--report", rep, "--model", ctx.model, *GEN],
        preexec=small_files,
    )
    ctx.expect("4. report write fails (RLIMIT_FSIZE)", got, 1, [str(rep), "cannot write the report"])


def case_temporaries_and_long_names(ctx):
    d = ctx.tmp / "n5"
    d.mkdir()
    ok_name = "s" * 247 + ".obj"  # output s...s.glb: 251 bytes; its visible temporary needed 262
    (d / ok_name).write_bytes(ctx.mesh.read_bytes())
    lst = d / "l.txt"
    lst.write_text(ok_name + "\n")
    got = ctx.batch(lst, ctx.tmp / "o5")
    ctx.expect("5. 251-byte output name", got, 0)
    if not (ctx.tmp / "o5" / ("s" * 247 + ".glb")).exists():
        ctx.failures.append("5. the 251-byte output was not written")
    leftovers = [f.name for f in (ctx.tmp / "o5").iterdir() if ".tmp" in f.name]
    if leftovers:
        ctx.failures.append(f"5. temporaries left: {leftovers}")
    long_out = ctx.tmp / ("L" * 252 + ".glb")
    got = ctx.run([ctx.silkgen, ctx.mesh, "-o", long_out, "--model", ctx.model, *GEN])
    ctx.expect("5. 256-byte output name, refused before generating", got, 1, ["256 bytes"], seconds=2.0)


def case_shards(ctx):
    lst = ctx.tmp / "l6.txt"
    lst.write_text(f"{ctx.mesh}\n")
    ctx.expect('6. --shard ""', ctx.batch(lst, ctx.tmp / "o6", "--shard", ""), 2, ["--shard", "''"])
    for env, word in (
        ({"SLURM_ARRAY_TASK_ID": ""}, "SLURM_ARRAY_TASK_ID=''"),
        ({"SLURM_ARRAY_TASK_COUNT": "4"}, "without SLURM_ARRAY_TASK_ID"),
        (
            {"SLURM_ARRAY_TASK_ID": "1", "SLURM_ARRAY_TASK_COUNT": "2", "SLURM_ARRAY_TASK_STEP": ""},
            "SLURM_ARRAY_TASK_STEP=''",
        ),
        (
            {"SLURM_ARRAY_TASK_ID": "1", "SLURM_ARRAY_TASK_COUNT": "2", "SLURM_ARRAY_TASK_MIN": "-1"},
            "SLURM_ARRAY_TASK_MIN='-1'",
        ),
        ({"SLURM_ARRAY_TASK_ID": "1e3", "SLURM_ARRAY_TASK_COUNT": "2"}, "1e3"),
    ):
        ctx.expect(f"6. {env}", ctx.batch(lst, ctx.tmp / "o6", env=env), 2, [word])
    if (ctx.tmp / "o6").exists() and any((ctx.tmp / "o6").glob("*.glb")):
        ctx.failures.append("6. an output was written with a refused shard")


def check_batch(ctx):
    for case in (
        case_inputs_in_outdir,
        case_nul_and_control_lines,
        case_report_is_input_or_list,
        case_report_write_fails,
        case_temporaries_and_long_names,
        case_shards,
    ):
        case(ctx)


def case_fifo(ctx):
    fifo = ctx.tmp / "pipe.obj"
    os.mkfifo(fifo)
    lst = ctx.tmp / "l8.txt"
    lst.write_text(f"{fifo}\n{ctx.mesh}\n")
    got = ctx.run(
        ["timeout", "15", ctx.silkgen, "--batch", lst, "-o", ctx.tmp / "o8", "--model", ctx.model, *GEN], timeout=30
    )
    ctx.expect("8. a FIFO in the list", got, 1, ["pipe.obj", "FIFO"])
    rows = {pathlib.Path(r["input"]).name: r["status"] for r in report_lines(ctx.tmp / "o8/silkgen_batch.jsonl")}
    if rows != {"pipe.obj": "failed", ctx.mesh.name: "ok"}:
        ctx.failures.append(f"8. rows {rows}: the FIFO failed alone, the mesh ok")
    folder = ctx.tmp / "f8"
    folder.mkdir()
    os.mkfifo(folder / "pipe.obj")
    (folder / "knot.obj").write_bytes(ctx.mesh.read_bytes())
    got = ctx.run(
        ["timeout", "15", ctx.silkgen, "--batch", folder, "-o", ctx.tmp / "o8d", "--model", ctx.model, *GEN], timeout=30
    )
    ctx.expect("8. a FIFO in a --batch folder", got, 1, ["pipe.obj", "FIFO"])
    fifo_list = ctx.tmp / "list.fifo"
    os.mkfifo(fifo_list)
    ctx.expect(
        "8. a FIFO as the list",
        ctx.run(
            ["timeout", "15", ctx.silkgen, "--batch", fifo_list, "-o", ctx.tmp / "o8f", "--model", ctx.model, *GEN]
        ),
        1,
        ["FIFO"],
    )
    ctx.expect(
        "8. silktok stats on a FIFO",
        ctx.run(["timeout", "15", ctx.silktok, "stats", fifo]),
        1,
        ["silktok: I/O error: ", "FIFO"],
    )


def case_dev_zero_and_long_list(ctx):
    link = ctx.tmp / "zero.obj"
    os.symlink("/dev/zero", link)
    got = ctx.rss([ctx.silktok, "stats", link])
    ctx.expect("9. silktok stats on a symlink to /dev/zero", got, 1, ["zero.obj", "character device"])
    if got[3] > 512:
        ctx.failures.append(f"9. /dev/zero: peak {got[3]:.0f} MB")
    lst = ctx.tmp / "long.txt"
    with open(lst, "wb") as f:
        f.write(b"a" * (64 * 1000 * 1000) + b"\n")
    out = ctx.tmp / "o9"
    got = ctx.rss([ctx.silkgen, "--batch", lst, "-o", out, "--model", ctx.model, *GEN])
    ctx.expect("9. a 64 MB one-line list", got, 1, ["longer than a path"])
    if got[3] > 512:
        ctx.failures.append(f"9. 64 MB list: peak {got[3]:.0f} MB")
    lines = (out / "silkgen_batch.jsonl").read_bytes().splitlines()
    if len(lines) != 1 or len(lines[0]) >= 65536:
        ctx.failures.append(f"9. report: {len(lines)} line(s), longest {max(map(len, lines), default=0)} bytes")


def case_single_runs(ctx):
    inp = ctx.tmp / "single.obj"
    inp.write_bytes(ctx.mesh.read_bytes())
    before = fingerprint([inp])
    ply = ctx.tmp / "single.ply"
    ply.write_bytes((ctx.repo / "tests/models/golden/torus_knot_points.ply").read_bytes())
    before.update(fingerprint([ply]))
    for src, opt in ((inp, "-o"), (inp, "--tokens"), (inp, "--stats"), (ply, "--save-points")):
        extra = ["-o", ctx.tmp / "x.glb"] if opt != "-o" else []
        got = ctx.run([ctx.silkgen, src, opt, src, *extra, "--model", ctx.model, *GEN])
        ctx.expect(f"silkgen {opt} = the input", got, 1, ["silkgen: invalid argument: ", "never writes"], seconds=3)
    got = ctx.run([ctx.silkgen, inp, "-o", ctx.tmp / "same.glb", "--stats", ctx.tmp / "same.glb", "--model", ctx.model])
    ctx.expect("silkgen -o = --stats", got, 1, ["two outputs cannot share a file"], seconds=3)
    tok = ctx.tmp / "t.tokens.txt"
    subprocess.run([str(ctx.silktok), "encode", inp, "-o", tok], check=True, capture_output=True)
    before.update(fingerprint([tok]))
    ctx.expect("silktok encode -o = the input", ctx.run([ctx.silktok, "encode", inp, "-o", inp]), 1, ["never writes"])
    ctx.expect("silktok decode -o = the input", ctx.run([ctx.silktok, "decode", tok, "-o", tok]), 1, ["never writes"])
    ctx.expect("silktok repair -o = the input", ctx.run([ctx.silktok, "repair", tok, "-o", tok]), 1, ["never writes"])
    unchanged(ctx, "single runs", before)
    # The error line: "<tool>: <kind>: <file>: <problem>" for both tools.
    got = ctx.run([ctx.silkgen, "--batch", ctx.tmp / "missing.txt", "-o", ctx.tmp / "om", "--model", ctx.model])
    ctx.expect("error format: silkgen, a missing list", got, 1, ["silkgen: I/O error: ", "missing.txt"])
    got = ctx.run([ctx.silkgen, inp, "-o", ctx.tmp / "y.glb", "--seed", "x", "--model", ctx.model])
    ctx.expect("error format: silkgen --seed x", got, 2, ["silkgen: invalid argument: --seed"])


def check_files(ctx):
    for case in (case_fifo, case_dev_zero_and_long_list, case_single_runs):
        case(ctx)


def start_batch(ctx, lst, out, stderr):
    """silkgen --batch over the list, 2,000 ids a mesh on one thread (long enough to signal mid-run)."""
    args = ["--batch", lst, "-o", out, "--model", ctx.model, "--max-tokens", "2000", "--threads", "1", "-q"]
    return subprocess.Popen([str(ctx.silkgen), *map(str, args)], stderr=stderr)


def wait_for_first_mesh(p, out):
    """Until the run has written its first mesh (or ended): signals then land mid-run on a quiet
    machine too, where a fixed wait can outlast the whole run."""
    deadline = time.monotonic() + 30
    while p.poll() is None and time.monotonic() < deadline and not any(out.glob("*.glb")):
        time.sleep(0.002)


def check_signals(ctx):
    lst = ctx.tmp / "many.txt"
    copies = []
    for i in range(40):
        c = ctx.tmp / f"m{i:02d}.obj"
        c.write_bytes(ctx.mesh.read_bytes())
        copies.append(c)
    lst.write_text("".join(f"{c}\n" for c in copies))
    for sig, rc in ((signal.SIGTERM, 143), (signal.SIGINT, 130)):
        out = ctx.tmp / f"sig{sig}"
        p = start_batch(ctx, lst, out, subprocess.PIPE)
        wait_for_first_mesh(p, out)
        time.sleep(0.2)
        t0 = time.monotonic()
        p.send_signal(sig)
        try:
            _, err = p.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            p.kill()
            _, err = p.communicate()
        secs = time.monotonic() - t0
        ctx.expect(f"signal {sig.name}", (p.returncode, err.decode(), secs), rc, ["interrupted"], seconds=1.0)
        left = [f.name for f in out.iterdir() if ".tmp" in f.name] if out.exists() else []
        if left:
            ctx.failures.append(f"{sig.name}: temporaries left: {left}")
    check_two_sigterms(ctx, lst)


def check_two_sigterms(ctx, lst):
    """Two signals 20 ms apart: the second ends the process at once (as SIGTERM), after removing the
    temporary of a save in progress; repeated, a few milliseconds later each time, so some land
    during a save."""
    for attempt in range(5):
        out = ctx.tmp / f"twice{attempt}"
        p = start_batch(ctx, lst, out, subprocess.DEVNULL)
        wait_for_first_mesh(p, out)
        time.sleep(0.007 * attempt)
        if p.poll() is not None:  # the work must outlast the wait, or the signals test nothing
            ctx.failures.append(f"two SIGTERMs: the run ended (exit {p.returncode}) before the first signal")
            continue
        p.send_signal(signal.SIGTERM)
        time.sleep(0.02)
        if p.poll() is None:
            p.send_signal(signal.SIGTERM)
        p.wait(timeout=10)
        if p.returncode not in (-signal.SIGTERM, 143):
            ctx.failures.append(f"two SIGTERMs: exit {p.returncode}")
        left = [f.name for f in out.iterdir() if ".tmp" in f.name] if out.exists() else []
        if left:
            ctx.failures.append(f"two SIGTERMs: temporaries left: {left}")


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    checks = {"batch": check_batch, "files": check_files, "signals": check_signals}
    if mode not in checks or len(sys.argv) != 5:
        print(__doc__)
        return 2
    silkgen, silktok, repo = (pathlib.Path(a).resolve() for a in sys.argv[2:5])
    with tempfile.TemporaryDirectory() as tmp:
        ctx = Ctx(silkgen, silktok, repo, pathlib.Path(tmp))
        checks[mode](ctx)
    return finish(f"hostile files {mode}", ctx.failures)


if __name__ == "__main__":
    sys.exit(main())
