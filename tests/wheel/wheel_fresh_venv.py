#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""ctest wheel_fresh_venv (tests/CMakeLists.txt; runs only with SILK_TEST_WHEEL=1, else skipped with 77,
because it builds libsilk in Release and downloads onnxruntime and numpy from PyPI): the pip wheel as a
user gets it. Builds it with scripts/build_wheel.sh (or takes --wheel), installs it into a fresh venv
(no system site-packages; a private pip cache, whose size is the download) and runs everything from a
scratch folder with a clean environment, so nothing of the source or build tree is on any path:
  * the console scripts' launcher imports neither silk_mesh nor numpy (its cost is printed);
  * silkgen (console script) with the tiny model and the golden run's arguments: ids identical to
    tests/models/golden/torus_knot_s7.tokens.txt (the silkgen_golden ctest's golden);
  * silkgen with no --model (the bundled model) on samples/torus_knot.obj: ids identical to the build
    tree's silkgen with --model models/default on the same arguments (when --build-silkgen is given);
  * silktok encode of spec goldens = their official ids, and silk_mesh.encode = silktok's ids;
  * import silk_mesh: encode/decode/Model/generate with numpy arrays, bundled_model_dir() inside the
    installed package, libsilk and onnxruntime loaded from the venv;
  * silk-export without the train extra: exit 2 naming the missing packages and the pip command;
  * with the train extra, every silk-export command from the installed wheel outside the checkout:
    import-official of the official fixture by path and from a model hub on 127.0.0.1
    (tests/tools/local_hub.py) with --name, the two model folders compared file by file; silkgen
    --list-models and --model NAME on it; dataset on three meshes, two train steps, export --name of
    that checkpoint and silkgen --model on it. The train extra's packages (torch is 3 GB with its CUDA
    libraries) come from this interpreter's site-packages through a .pth file appended to the venv's path
    (--train-deps pypi downloads them instead); the .pth is removed afterwards;
  * onnxruntime uninstalled: silkgen fails naming the library file it tried; silktok still works.
Prints every command and its output (the transcript for docs and closing notes).
Usage: wheel_fresh_venv.py REPO SHARED [--wheel W] [--build-silkgen PATH] [--keep DIR] [--train-deps system|pypi]"""

import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time

GOLDEN_ARGS = [
    "--max-tokens",
    "300",
    "--threads",
    "1",
    "-q",
    "--surface-tolerance",
    "0",
    "--candidates",
    "1",
    "--orient",
    "tokens",
    "--face-guidance",
    "off",
]  # tests/tools/silkgen_checks.py COMMON
SPEC_GOLDENS = ["cube", "icosphere2", "cylinder_capped"]
FAILURES = []


def sh(cmd, env, cwd, check=True, show=True):
    t = time.monotonic()
    p = subprocess.run([str(c) for c in cmd], env=env, cwd=cwd, capture_output=True, text=True, timeout=1800)
    dt = time.monotonic() - t
    if show:
        print(f"$ {' '.join(map(str, cmd))}    # exit {p.returncode}, {dt:.2f} s")
        out = (p.stdout + p.stderr).strip()
        if out:
            print("\n".join(out.splitlines()[-25:]))
    if check and p.returncode != 0:
        raise SystemExit(f"FAILED: {' '.join(map(str, cmd))}\n{p.stdout}\n{p.stderr}")
    return p


def expect(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        FAILURES.append(what)


def build_wheel(repo, out):
    p = sh(["bash", repo / "scripts/build_wheel.sh", out], dict(os.environ), repo)
    return repo / p.stdout.strip().splitlines()[-1]  # the script prints the wheel's path last


def make_venv(tmp, wheel):
    venv = tmp / "venv"
    subprocess.run([sys.executable, "-m", "venv", venv], check=True)
    env = {
        "PATH": f"{venv}/bin:/usr/bin:/bin",
        "HOME": str(tmp),
        "PIP_CACHE_DIR": str(tmp / "pip-cache"),
        "PIP_DISABLE_PIP_VERSION_CHECK": "1",
        "LANG": "C.UTF-8",
    }
    for k in (
        "PIP_CERT",
        "PIP_INDEX_URL",
        "PIP_EXTRA_INDEX_URL",
        "PIP_DEFAULT_TIMEOUT",
        "SSL_CERT_FILE",
        "HTTPS_PROXY",
        "HTTP_PROXY",
        "https_proxy",
        "http_proxy",
        "NO_PROXY",
        "no_proxy",
    ):
        if k in os.environ:
            env[k] = os.environ[k]
    # Download, then install from the downloaded files alone: the download's size is what a user fetches.
    t = time.monotonic()
    sh([venv / "bin/pip", "download", "-q", "-d", tmp / "downloads", wheel], env, tmp)
    sh([venv / "bin/pip", "install", "-q", "--no-index", "--find-links", tmp / "downloads", wheel], env, tmp)
    dt = time.monotonic() - t
    cache = sum(f.stat().st_size for f in (tmp / "downloads").iterdir() if f.name != wheel.name)
    site = next((venv / "lib").glob("python3*/site-packages"))
    size = sum(f.stat().st_size for f in site.rglob("*") if f.is_file())
    ours = sum(
        f.stat().st_size
        for d in ("silk_mesh", "silk_mesh.libs", "silk_export")
        for f in (site / d).rglob("*")
        if f.is_file()
    )
    print(
        f"install: {dt:.1f} s, downloaded {cache / 1e6:.1f} MB from PyPI, site-packages {size / 1e6:.1f} MB "
        f"(silk_mesh + silk_mesh.libs + silk_export {ours / 1e6:.1f} MB)"
    )
    sh([venv / "bin/pip", "list"], env, tmp)
    return venv, env, site


def check_launcher(env, tmp, site):
    """The console scripts exec the bundled binaries without importing silk_mesh (numpy)."""
    p = sh(
        [
            "python",
            "-c",
            "import sys, silk_mesh_tools as t; print(t.tool_path('silkgen')); "
            "print('numpy imported:', 'numpy' in sys.modules)",
        ],
        env,
        tmp,
    )
    expect(
        p.stdout.split()[0] == str(site / "silk_mesh/bin/silkgen") and "numpy imported: False" in p.stdout,
        "console-script launcher: finds silk_mesh/bin/silkgen without importing silk_mesh or numpy",
    )
    for cmd in (["silktok", "--version"], [site / "silk_mesh/bin/silktok", "--version"]):
        t = time.monotonic()
        for _ in range(3):
            sh(cmd, env, tmp, show=False)
        print(f"{' '.join(map(str, cmd))}: {(time.monotonic() - t) / 3 * 1e3:.0f} ms per run")


def check_silkgen(repo, venv, env, tmp, build_silkgen):
    sample = repo / "samples/torus_knot.obj"
    sh(
        [
            "silkgen",
            sample,
            "-o",
            tmp / "tiny.obj",
            "--model",
            repo / "tests/models/tiny",
            "--seed",
            "7",
            "--tokens",
            tmp / "tiny.tokens.txt",
            *GOLDEN_ARGS,
        ],
        env,
        tmp,
    )
    golden = repo / "tests/models/golden/torus_knot_s7.tokens.txt"
    expect(
        (tmp / "tiny.tokens.txt").read_bytes() == golden.read_bytes(),
        f"wheel silkgen (tiny model) ids == {golden.relative_to(repo)}",
    )
    args = [sample, "--seed", "1", "--threads", "2", "--max-tokens", "600", "--candidates", "1"]
    sh(
        [
            "silkgen",
            *args,
            "-o",
            tmp / "torus_knot_gen.glb",
            "--tokens",
            tmp / "bundled.tokens.txt",
            "--stats",
            tmp / "bundled.json",
        ],
        env,
        tmp,
    )
    stats = json.loads((tmp / "bundled.json").read_text())
    print(
        f"bundled model: {stats.get('faces')} faces, {stats.get('tokens', stats.get('ids'))} ids, stop {stats.get('stop_reason')}"
    )
    expect(stats.get("faces", 0) > 0, "wheel silkgen with the bundled model (no --model) writes faces")
    if build_silkgen:
        sh(
            [
                build_silkgen,
                *args,
                "-q",
                "--model",
                repo / "models/default",
                "-o",
                tmp / "ref.glb",
                "--tokens",
                tmp / "ref.tokens.txt",
            ],
            dict(os.environ),
            tmp,
            show=False,
        )
        expect(
            (tmp / "bundled.tokens.txt").read_bytes() == (tmp / "ref.tokens.txt").read_bytes(),
            f"wheel silkgen (bundled model) ids == {build_silkgen} --model models/default, same arguments",
        )


def check_silktok_and_python(repo, shared, env, tmp, site):
    for name in SPEC_GOLDENS:
        sh(["silktok", "encode", shared / f"spec/golden/{name}.obj", "-o", tmp / f"{name}.tokens.txt"], env, tmp)
        expect(
            (tmp / f"{name}.tokens.txt").read_text().split()
            == (shared / f"spec/golden/{name}.tokens.txt").read_text().split(),
            f"silktok encode {name} == official ids",
        )
    code = f"""
import os, numpy, silk_mesh
print("silk_mesh", silk_mesh.version(), "from", silk_mesh.__file__)
print("libsilk", silk_mesh.library_path())
for name in {SPEC_GOLDENS!r}:
    ids = silk_mesh.encode({str(shared)!r} + f"/spec/golden/{{name}}.obj")
    cli = [int(x) for x in open(f"{{name}}.tokens.txt").read().split()]
    assert ids == cli, (name, len(ids), len(cli))
    print(name, "encode:", len(ids), "ids == silktok encode")
mesh = silk_mesh.decode(ids)
print("decode:", type(mesh.positions).__name__, mesh.positions.dtype, mesh.positions.shape, mesh.triangles.shape)
assert isinstance(mesh.positions, numpy.ndarray) and isinstance(mesh.triangles, numpy.ndarray)
d = silk_mesh.bundled_model_dir()
print("bundled_model_dir:", d)
assert d.startswith(os.path.dirname(silk_mesh.__file__)) and os.path.isfile(d + "/model.json"), d
with silk_mesh.Model() as m:
    print("Model():", m.dir, {{k: m.info()[k] for k in ("decoder", "default_points")}})
    r = silk_mesh.generate({str(repo / "samples/torus_knot.obj")!r}, model=m, seed=1, max_tokens=300)
print("generate:", len(r.ids), "ids,", r.mesh.triangles.shape[0], "faces, stop", r.stats["stop_reason"])
maps = open("/proc/self/maps").read()
ort = sorted({{l.split()[-1] for l in maps.splitlines() if "libonnxruntime" in l}})
print("onnxruntime loaded from:", ort)
assert len(ort) == 1 and ort[0].startswith({str(site)!r}), ort
"""
    sh(["python", "-c", code], env, tmp)
    print("ok: silk_mesh (encode == silktok, decode, numpy arrays, bundled Model, generate, onnxruntime from the venv)")


def check_no_train_extra(env, tmp):
    p = sh(["silk-export", "--help"], env, tmp, check=False)
    expect(
        p.returncode == 2 and "silk-mesh[train]" in p.stderr and "torch" in p.stderr,
        "silk-export without the train extra: exit 2 naming torch and pip install 'silk-mesh[train]'",
    )


def install_train_extra(venv, env, tmp, site, wheel, deps):
    """The train extra into the venv: from PyPI, or this interpreter's installed packages (a .pth line
    appends its site-packages to the venv's path; its own .pth files, e.g. editable installs, are not run)."""
    pth = site / "silk-test-train-deps.pth"
    if deps == "system":
        pth.write_text(sysconfig.get_paths()["purelib"] + "\n")
        # The venv's own old setuptools would hide the interpreter's (torch needs setuptools >= 77).
        sh([venv / "bin/pip", "uninstall", "-q", "-y", "setuptools"], env, tmp, check=False)
        sh(
            [venv / "bin/pip", "install", "-q", "--no-index", "--find-links", tmp / "downloads", f"{wheel}[train]"],
            env,
            tmp,
        )
    else:
        sh([venv / "bin/pip", "install", "-q", f"{wheel}[train]"], env, tmp)
    p = sh(["python", "-c", "import silk_export, torch, huggingface_hub; print(silk_export.__file__)"], env, tmp)
    expect(p.stdout.strip().startswith(str(site / "silk_export")), "silk_export is the wheel's copy in the venv")
    return pth


def compare_folders(a, b):
    """Prints each file of the two model folders (bytes, same or not); True when the ONNX files are identical and
    model.json differs only in timings and the recorded hub source."""
    names = sorted({f.name for f in a.iterdir()} | {f.name for f in b.iterdir()})
    ok = True
    for n in names:
        fa, fb = a / n, b / n
        same = fa.is_file() and fb.is_file() and fa.read_bytes() == fb.read_bytes()
        print(
            f"  {n:28} {fa.stat().st_size if fa.is_file() else '-':>10} {fb.stat().st_size if fb.is_file() else '-':>10}"
            f"  {'identical' if same else 'differs'}"
        )
        ok = ok and (same or n in ("model.json", "MODEL_CARD.md"))

    def strip(o):
        if isinstance(o, dict):
            return {k: strip(v) for k, v in o.items() if k not in ("ms_per_token", "seconds", "hub", "url")}
        return [strip(v) for v in o] if isinstance(o, list) else o

    ja, jb = (json.loads((d / "model.json").read_text()) for d in (a, b))
    print(f"  model.json: hub source {jb['source'].get('hub')}")
    return ok and strip(ja) == strip(jb) and "hub" in jb["source"]


def check_official_import(repo, shared, env, tmp):
    fixture = shared / "official-fixture"
    sys.path.insert(0, str(repo / "tests/tools"))
    from local_hub import LocalHub

    sh(
        [
            "silk-export",
            "import-official",
            fixture / "model.safetensors",
            "--config",
            fixture / "config.json",
            "-o",
            tmp / "fixture-by-path",
            "--precision",
            "fp32",
            "--no-progress",
        ],
        env,
        tmp,
    )
    henv = {**env, "HF_HOME": str(tmp / "hf-home"), "SILK_MODELS": str(tmp / "models"), "HF_HUB_DISABLE_TELEMETRY": "1"}
    with LocalHub({"gcsong/mesh_silksong": fixture}) as hub:
        henv["HF_ENDPOINT"] = hub.endpoint
        sh(
            [
                "silk-export",
                "import-official",
                "hf:gcsong/mesh_silksong/model.safetensors",
                "--config",
                "hf:gcsong/mesh_silksong/config.json",
                "--name",
                "fixture",
                "--precision",
                "fp32",
                "--no-progress",
            ],
            henv,
            tmp,
        )
    print("file by file: by path (bytes), from the hub (bytes)")
    expect(
        compare_folders(tmp / "fixture-by-path", tmp / "models/fixture"),
        "import-official by path and from the local hub: identical ONNX files, model.json equal but for timings",
    )
    p = sh(["silkgen", "--list-models"], henv, tmp)
    expect(
        any(l.startswith("fixture ") and "official" in l for l in p.stdout.splitlines()),
        "silkgen --list-models lists the imported model by name with its architecture",
    )
    sh(
        [
            "silkgen",
            repo / "samples/torus_knot.obj",
            "-o",
            tmp / "fixture.glb",
            "--model",
            "fixture",
            "--max-tokens",
            "64",
            "--seed",
            "1",
            "--threads",
            "1",
        ],
        henv,
        tmp,
    )
    expect((tmp / "fixture.glb").is_file(), "silkgen --model fixture (a name) runs the imported model")
    return henv


def check_train_path(repo, shared, henv, tmp):
    meshes = tmp / "meshes"
    meshes.mkdir()
    for m in sorted((shared / "corpus/dev").glob("*.obj"))[:3]:
        shutil.copy(m, meshes / m.name)
    p = sh(["silk-export", "dataset", "--root", meshes, "--out", tmp / "ds"], henv, tmp, check=False)
    expect(
        p.returncode != 0 and "--dev-dir" in p.stderr and "SILK_SHARED_DIR" in p.stderr,
        "silk-export dataset with no dev corpus named: a message naming --dev-dir, SILK_SHARED_DIR, --all-train",
    )
    sh(["silk-export", "dataset", "--root", meshes, "--out", tmp / "ds", "--all-train"], henv, tmp)
    sh(
        [
            "silk-export",
            "train",
            "--data",
            tmp / "ds",
            "--out",
            tmp / "run",
            "--config",
            "tiny",
            "--steps",
            "2",
            "--no-progress",
            "--val-every",
            "1000",
        ],
        henv,
        tmp,
    )
    sh(
        ["silk-export", "export", "--checkpoint", tmp / "run/checkpoint.pt", "--name", "tiny-trained", "--no-int8"],
        henv,
        tmp,
    )
    sh(
        [
            "silkgen",
            repo / "samples/torus_knot.obj",
            "-o",
            tmp / "trained.glb",
            "--model",
            "tiny-trained",
            "--max-tokens",
            "64",
            "--threads",
            "1",
        ],
        henv,
        tmp,
    )
    expect(
        (tmp / "models/tiny-trained/model.json").is_file() and (tmp / "trained.glb").is_file(),
        "dataset (3 meshes) -> 2 train steps -> export --name -> silkgen --model NAME, all from the wheel",
    )


def check_no_onnxruntime(venv, env, tmp, repo):
    sh([venv / "bin/pip", "uninstall", "-q", "-y", "onnxruntime"], env, tmp)
    p = sh(["silkgen", repo / "samples/torus_knot.obj", "-o", tmp / "no_ort.glb", "-q"], env, tmp, check=False)
    expect(
        p.returncode != 0 and "onnxruntime/capi/libonnxruntime.so" in p.stderr and "No such file" in p.stderr,
        "without onnxruntime: silkgen fails naming the library file and the reason",
    )
    p = sh(["silktok", "encode", repo / "samples/torus_knot.obj", "-o", tmp / "t.txt"], env, tmp, check=False)
    expect(p.returncode == 0, "without onnxruntime: silktok (no generation) still works")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("repo", type=pathlib.Path)
    ap.add_argument("shared", type=pathlib.Path)
    ap.add_argument("--wheel", type=pathlib.Path)
    ap.add_argument("--build-silkgen")
    ap.add_argument("--keep", type=pathlib.Path, help="work folder kept afterwards (default: a temporary one)")
    ap.add_argument(
        "--train-deps",
        choices=["system", "pypi"],
        default="system",
        help="the train extra's packages: this interpreter's (default) or downloaded from PyPI",
    )
    a = ap.parse_args()
    if not a.wheel and os.environ.get("SILK_TEST_WHEEL") != "1":
        print("skipped: set SILK_TEST_WHEEL=1 (builds the wheel in Release, downloads onnxruntime and numpy)")
        return 77
    repo, shared = a.repo.resolve(), a.shared.resolve()
    tmp = a.keep.resolve() if a.keep else pathlib.Path(tempfile.mkdtemp(prefix="silk-wheel-"))
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    t = time.monotonic()
    wheel = a.wheel.resolve() if a.wheel else build_wheel(repo, tmp / "dist")
    print(f"wheel: {wheel.name}, {wheel.stat().st_size / 1e6:.1f} MB (build {time.monotonic() - t:.0f} s)")
    venv, env, site = make_venv(tmp, wheel)
    check_launcher(env, tmp, site)
    check_silkgen(repo, venv, env, tmp, a.build_silkgen)
    check_silktok_and_python(repo, shared, env, tmp, site)
    check_no_train_extra(env, tmp)
    pth = install_train_extra(venv, env, tmp, site, wheel, a.train_deps)
    henv = check_official_import(repo, shared, env, tmp)
    check_train_path(repo, shared, henv, tmp)
    pth.unlink(missing_ok=True)
    check_no_onnxruntime(venv, env, tmp, repo)
    if not a.keep:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"{len(FAILURES)} failure(s)" + ("".join(f"\n  {f}" for f in FAILURES)))
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
