#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""silkgen with model.json version 3 (docs/model_contract.md), run by ctest (tests/cli/silkgen.cmake)
on COPIES of the committed tiny model made at test time:

  defaults   v3 "sampling"/"preprocessing" are silkgen's defaults and explicit options override
             them (tokens compared with the v2 model run with the same explicit settings); the
             official pre-processing runs; an INT4 default decoder is used when its file exists
  errors     missing external data, a default decoder without its file, an encoder whose fixed
             point count differs from dims.n_points; a decoder stored with external data loads and
             gives the same ids (the last two need the onnx package, else skipped)
  raw        --raw-points: the points reach the encoder exactly as written (float32 and float64
             PLY, checked through --trace), --tokens works without -o, and a wrong point count,
             a mesh input, or a non-finite value are clear errors
Usage: silkgen_v3_checks.py SILKGEN REPO"""

import json
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile

from check_report import finish

COMMON = ["--max-tokens", "120", "--threads", "1", "-q"]


def run(cmd):
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=300)


def v3_model(repo, dest, **changes):
    shutil.copytree(repo / "tests/models/tiny", dest)
    meta = json.loads((dest / "model.json").read_text())
    meta["model_version"] = 3
    meta["arch"] = "silk"
    meta.pop("normalize_bound", None)
    meta["preprocessing"] = {"kind": "silk", "normalize_bound": 0.95, "n_points": meta["dims"]["n_points"]}
    meta["sampling"] = {"temperature": 0.0, "top_k": 50, "top_p": 1.0, "top_p_temperature": 0.0}
    for key, value in changes.items():
        if isinstance(value, dict) and isinstance(meta.get(key), dict):
            meta[key].update(value)
        else:
            meta[key] = value
    (dest / "model.json").write_text(json.dumps(meta, indent=1, allow_nan=False))
    return dest


def nokv_int8(repo, tmp):
    """The tiny model without its int8-cache variant."""
    dest = v3_model(repo, tmp / "v3_nokv8")
    meta = json.loads((dest / "model.json").read_text())
    meta["files"].pop("kv_int8", None)
    (dest / "model.json").write_text(json.dumps(meta, indent=1))
    return dest


def write_cloud_ply(path, rows, double=False):
    t, fmt = ("double", "<6d") if double else ("float", "<6f")
    head = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(rows)
    head += "".join(f"property {t} {a}\n" for a in ("x", "y", "z", "nx", "ny", "nz")) + "end_header\n"
    path.write_bytes(head.encode() + b"".join(struct.pack(fmt, *r) for r in rows))


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def cloud(n):
    import math

    rows = []
    for i in range(n):
        a, b = 2 * math.pi * i / n, 0.7 * i
        p = (0.6 * math.cos(a), 0.6 * math.sin(a), 0.3 * math.sin(b))
        rows.append(tuple(f32(v) for v in (*p, math.cos(a), math.sin(a), 0.0)))
    return rows


def expect_fail(failures, label, p, words):
    if p.returncode == 0:
        failures.append(f"{label}: succeeded, expected an error")
    for w in words:
        if w.lower() not in p.stderr.lower():
            failures.append(f"{label}: stderr lacks '{w}': {p.stderr.strip()}")


def tokens_of(silkgen, model, inp, tmp, name, extra=()):
    tok, stats = tmp / f"{name}.txt", tmp / f"{name}.json"
    p = run([silkgen, inp, "--model", model, "--tokens", tok, "--stats", stats, *COMMON, *extra])
    if p.returncode != 0:
        return None, None, p.stderr.strip()
    return tok.read_text(), json.loads(stats.read_text()), ""


def check_defaults(silkgen, repo, tmp):
    failures = []
    sample = repo / "samples/torus_knot.obj"
    v2 = repo / "tests/models/tiny"
    v3 = v3_model(repo, tmp / "v3")
    base = ["--seed", "7"]
    got, st, err = tokens_of(silkgen, v3, sample, tmp, "v3_default", base)
    want, _, _ = tokens_of(silkgen, v2, sample, tmp, "v2_greedy", [*base, "--temperature", "0"])
    if got is None or got != want or st["settings"]["temperature"] != 0:
        failures.append(f"v3 default temperature 0 != v2 --temperature 0 ({err})")
    got, st, err = tokens_of(silkgen, v3, sample, tmp, "v3_override", [*base, "--temperature", "0.5"])
    want, _, _ = tokens_of(silkgen, v2, sample, tmp, "v2_default", base)
    if got is None or got != want or st["settings"]["temperature"] != 0.5:
        failures.append(f"v3 --temperature 0.5 != v2 defaults ({err})")
    off = v3_model(repo, tmp / "v3_official", preprocessing={"kind": "official", "surface_samples": 5000})
    got, st, err = tokens_of(silkgen, off, sample, tmp, "v3_official", base)
    if got is None or st["settings"]["preprocessing"] != "official":
        failures.append(f"official pre-processing run failed: {err}")
    got2, st2, _ = tokens_of(silkgen, v3, sample, tmp, "v3_pre_override", [*base, "--preprocessing", "official"])
    if got2 is None or st2["settings"]["preprocessing"] != "official":
        failures.append("--preprocessing official did not override the model's silk kind")
    int4 = v3_model(
        repo,
        tmp / "v3_int4",
        files={
            "encoder": "encoder.onnx",
            "decoder": "decoder.onnx",
            "decoder_int4": "decoder.int4.onnx",
            "default_decoder": "decoder_int4",
        },
    )
    shutil.copy(int4 / "decoder.onnx", int4 / "decoder.int4.onnx")  # same graph: only the selection is tested
    got, st, err = tokens_of(silkgen, int4, sample, tmp, "v3_int4", base)
    if got is None or st.get("decoder") != "int4":
        failures.append(f"default_decoder decoder_int4 not used: {err} {st and st.get('decoder')}")
    got, st, err = tokens_of(silkgen, int4, sample, tmp, "v3_fp32", [*base, "--decoder", "fp32"])
    if got is None or st.get("decoder") != "fp32":
        failures.append(f"--decoder fp32 did not override: {err}")
    kv16 = v3_model(repo, tmp / "v3_kv16", files={"default_kv_precision": "fp16"})
    got, st, err = tokens_of(silkgen, kv16, sample, tmp, "v3_kv16", base)
    if got is None or st.get("kv_precision") != "fp16":
        failures.append(f"default_kv_precision fp16 not used: {err} {st and st.get('kv_precision')}")
    elif st.get("kv_cache_bytes") * 2 != tokens_of(
        silkgen, kv16, sample, tmp, "v3_kv32", [*base, "--kv-precision", "fp32"]
    )[1].get("kv_cache_bytes"):
        failures.append("--kv-precision fp32 did not override the model's fp16 (or the cache is not half the size)")
    kv8 = v3_model(repo, tmp / "v3_kv8", files={"default_kv_precision": "int8"})
    got, st, err = tokens_of(silkgen, kv8, sample, tmp, "v3_kv8", base)
    d = json.loads((kv8 / "model.json").read_text())["dims"]["head_dim"]
    if got is None or st.get("kv_precision") != "int8":
        failures.append(f"default_kv_precision int8 not used: {err} {st and st.get('kv_precision')}")
    elif st.get("kv_cache_bytes") * 4 * d != tokens_of(
        silkgen, kv8, sample, tmp, "v3_kv8_32", [*base, "--kv-precision", "fp32"]
    )[1].get("kv_cache_bytes") * (d + 4):
        failures.append("the int8 cache is not (head_dim + 4) / (4 head_dim) of the fp32 cache's bytes")
    return failures


def check_errors(silkgen, repo, tmp):
    failures = []
    sample = repo / "samples/torus_knot.obj"
    ext = v3_model(repo, tmp / "v3_ext", files={"external_data": ["decoder.onnx.data"]})
    expect_fail(
        failures,
        "missing external data",
        run([silkgen, sample, "--model", ext, "--tokens", tmp / "t", "-q"]),
        ["decoder.onnx.data", "missing"],
    )
    nofile = v3_model(
        repo, tmp / "v3_noint4", files={"decoder_int4": "decoder.int4.onnx", "default_decoder": "decoder_int4"}
    )
    expect_fail(
        failures,
        "absent int4 file",
        run([silkgen, sample, "--model", nofile, "--tokens", tmp / "t", "-q"]),
        ["decoder.int4.onnx", "missing"],
    )
    expect_fail(
        failures,
        "--decoder int8 without file",
        run([silkgen, sample, "--model", repo / "tests/models/tiny", "--decoder", "int8", "--tokens", tmp / "t", "-q"]),
        ["INT8"],
    )
    nokv = v3_model(repo, tmp / "v3_nokv", files={"kv_fp16": {}})
    expect_fail(
        failures,
        "--kv-precision fp16 without a variant",
        run([silkgen, sample, "--model", nokv, "--kv-precision", "fp16", "--tokens", tmp / "t", "-q"]),
        ["fp16", str(nokv)],
    )
    expect_fail(
        failures,
        "--kv-precision int8 without a variant",
        run([silkgen, sample, "--model", nokv_int8(repo, tmp), "--kv-precision", "int8", "--tokens", tmp / "t", "-q"]),
        ["int8", "files.kv_int8", "silk-export kv8"],
    )
    try:
        import onnx
    except ImportError:
        print("silkgen v3 errors: onnx not installed, the point-count mismatch check is skipped")
        return failures
    fixed = v3_model(repo, tmp / "v3_fixed_n")
    enc = onnx.load(str(fixed / "encoder.onnx"))
    enc.graph.input[0].type.tensor_type.shape.dim[1].dim_value = 128
    onnx.save(enc, str(fixed / "encoder.onnx"))
    expect_fail(
        failures,
        "encoder point count",
        run([silkgen, sample, "--model", fixed, "--tokens", tmp / "t", "-q"]),
        ["takes 128 points", "n_points is 256"],
    )
    # A decoder whose weights live in external data next to it loads (sessions from paths).
    ext_ok = v3_model(repo, tmp / "v3_external", files={"external_data": ["decoder.onnx.data"]})
    dec = onnx.load(str(ext_ok / "decoder.onnx"))
    onnx.save_model(
        dec,
        str(ext_ok / "decoder.onnx"),
        save_as_external_data=True,
        all_tensors_to_one_file=True,
        location="decoder.onnx.data",
        size_threshold=0,
    )
    plain, _, _ = tokens_of(silkgen, v3_model(repo, tmp / "v3_plain"), sample, tmp, "plain", ["--seed", "3"])
    got, _, err = tokens_of(silkgen, ext_ok, sample, tmp, "external", ["--seed", "3"])
    if got is None or got != plain or (ext_ok / "decoder.onnx").stat().st_size > 100000:
        failures.append(f"decoder with external data: {err or 'tokens differ / data not external'}")
    return failures


def check_raw(silkgen, repo, tmp):
    failures = []
    model = repo / "tests/models/tiny"
    rows = cloud(256)
    for double in (False, True):
        ply = tmp / f"raw_{'f64' if double else 'f32'}.ply"
        write_cloud_ply(ply, rows, double)
        tok, trace = tmp / f"raw_{double}.txt", tmp / f"raw_{double}.trace.json"
        p = run([silkgen, ply, "--model", model, "--raw-points", "--tokens", tok, "--trace", trace, *COMMON])
        if p.returncode != 0:
            failures.append(f"--raw-points ({'float64' if double else 'float32'}) failed: {p.stderr.strip()}")
            continue
        pts = json.loads(trace.read_text())["points"]
        if [f32(v) for v in pts] != [v for r in rows for v in r]:  # the trace prints 9 digits
            failures.append("--raw-points: the encoder input differs from the file's values")
        if not tok.read_text().strip():
            failures.append("--raw-points: no tokens written")
    if (
        (tmp / "raw_False.txt").exists()
        and (tmp / "raw_True.txt").exists()
        and (tmp / "raw_False.txt").read_text() != (tmp / "raw_True.txt").read_text()
    ):
        failures.append("--raw-points: float32 and float64 files of the same values gave different tokens")
    short = tmp / "raw_short.ply"
    write_cloud_ply(short, rows[:100])
    expect_fail(
        failures,
        "raw count",
        run([silkgen, short, "--model", model, "--raw-points", "--tokens", tmp / "t"]),
        ["100 points", "takes 256"],
    )
    expect_fail(
        failures,
        "raw mesh",
        run([silkgen, repo / "samples/torus_knot.obj", "--model", model, "--raw-points", "--tokens", tmp / "t"]),
        ["point-cloud PLY"],
    )
    bad = list(rows)
    bad[5] = (float("nan"),) + bad[5][1:]
    nan = tmp / "raw_nan.ply"
    write_cloud_ply(nan, bad)
    p = run([silkgen, nan, "--model", model, "--raw-points", "--tokens", tmp / "t"])
    if p.returncode == 0:
        failures.append("--raw-points accepted a NaN coordinate")
    p = run([silkgen, short, "--model", model, "--raw-points"])
    if p.returncode != 2 or "--tokens" not in p.stderr:
        failures.append(f"no -o and no --tokens: exit {p.returncode}, {p.stderr.strip()}")
    return failures


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    mode, silkgen, repo = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    checks = {"defaults": check_defaults, "errors": check_errors, "raw": check_raw}
    if mode not in checks:
        print(__doc__)
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        failures = checks[mode](silkgen, repo, pathlib.Path(tmp))
    return finish(f"silkgen v3 {mode}", failures)


if __name__ == "__main__":
    sys.exit(main())
