# SPDX-License-Identifier: MIT
"""`silk-export` console script: dataset | train | export | import-official | eval | card, plus
bench | generate | loss."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from .json_io import dumps
from .model_names import add_output_arguments, output_folder
from .models.configs import CONFIGS
from .onnx.kv_precision import KV_PRECISIONS

# One pair per sub-command: _add_<command> declares its arguments, _cmd_<command> runs it.


def _add_dataset(sub) -> None:
    d = sub.add_parser("dataset", help="encode a mesh collection through libsilk into a sharded token cache")
    d.add_argument("--root", help="0 A.D. cache ($SILK_DATA_DIR/0ad, default) or any folder tree of meshes")
    d.add_argument("--out", required=True, help="dataset folder (shards, index.jsonl, dataset.json, refused.tsv)")
    d.add_argument("--shard", help="I/N: build only shard I of N (files I, I+N, ...); then --merge")
    d.add_argument("--merge", action="store_true", help="merge the finished shards in --out into the index")
    d.add_argument("--dev-dir", help="dev corpus folder (default: <shared>/corpus/dev)")
    d.add_argument("--all-train", action="store_true", help="every mesh is training data (no splits, no dev exclusion)")
    d.add_argument("--limit", type=int, help="index only the first N files (sorted)")
    d.set_defaults(fn=_cmd_dataset)


def _cmd_dataset(a) -> int:
    from .data.dataset_index import build_index, build_shard, merge_shards
    from .data.mesh_files import default_0ad_root
    from .data.shard_store import parse_shard

    root = Path(a.root) if a.root else default_0ad_root()
    dev = Path(a.dev_dir) if a.dev_dir else None
    if a.merge:
        summary = merge_shards(Path(a.out))
    elif a.shard:
        path = build_shard(root, Path(a.out), parse_shard(a.shard), dev, a.limit, a.all_train)
        summary = json.loads((path / "shard.json").read_text())
    else:
        summary = build_index(root, Path(a.out), dev, a.limit, a.all_train)
    print(dumps(summary, "null", indent=2))
    return 0


def _add_train(sub) -> None:
    t = sub.add_parser("train", help="train a model (resumes from OUT/checkpoint.pt); runs under torchrun too")
    t.add_argument("--data", help="dataset folder from `silk-export dataset`, or any folder of meshes (quick runs)")
    t.add_argument("--index", help="index.jsonl of mesh files under --root (instead of --data)")
    t.add_argument("--root", help="folder the index's `file` paths are relative to (default: 0 A.D. cache)")
    t.add_argument("--out", required=True)
    t.add_argument("--config", default="micro", choices=sorted(CONFIGS))
    t.add_argument("--steps", type=int, default=1000)
    t.add_argument("--batch-size", type=int, default=4, help="global batch: sequences per step over all ranks")
    t.add_argument(
        "--micro-batch",
        type=int,
        default=0,
        help="sequences per forward/backward, the rest accumulated (0: 1 on CPU, the rank's share on CUDA)",
    )
    t.add_argument("--lr", type=float, help="peak LR (default 1e-4; 2e-5 with --init-from)")
    t.add_argument("--lr-min", type=float, help="final LR (default 5e-5; 2e-6 with --init-from)")
    t.add_argument("--warmup", type=int, help="warm-up steps (default 0; min(200, steps/10) with --init-from)")
    t.add_argument("--seed", type=int, default=0)
    t.add_argument("--threads", type=int, default=0)
    t.add_argument("--device", default="auto")
    t.add_argument(
        "--precision", default="auto", choices=["auto", "fp32", "bf16"], help="auto: bf16 autocast on CUDA, fp32 on CPU"
    )
    t.add_argument("--grad-checkpoint", action="store_true", help="recompute decoder layers in backward")
    t.add_argument("--fsdp", action="store_true", help="shard parameters/gradients/optimizer (FSDP2) instead of DDP")
    t.add_argument("--workers", type=int, default=0, help="DataLoader processes per rank preparing samples")
    t.add_argument(
        "--init-from",
        help="fine-tune a released-format Mesh Silksong checkpoint (model.safetensors, "
        ".pt/.bin; the official architecture, loaded as import-official does)",
    )
    t.add_argument(
        "--init-config",
        help="with --init-from: JSON in the official fixture's config.json format "
        "(values no shape reveals, as import-official --config)",
    )
    t.add_argument("--log-every", type=int, default=10)
    t.add_argument("--val-every", type=int, default=200)
    t.add_argument("--val-meshes", type=int, default=32)
    t.add_argument("--ckpt-minutes", type=float, default=5.0)
    t.add_argument(
        "--max-minutes",
        type=float,
        default=0.0,
        help="stop (and checkpoint) after this many minutes of this invocation (training that spans sessions)",
    )
    t.add_argument(
        "--max-cpu-minutes",
        type=float,
        default=0.0,
        help="stop (and checkpoint) after this much CPU time of this process (comparing configurations "
        "at equal compute on a shared machine; use with --workers 0)",
    )
    t.add_argument("--max-seq-len", type=int, default=0, help="override the config's max_seq_len")
    t.add_argument("--no-resume", action="store_true")
    t.add_argument("--no-augment", action="store_true")
    t.add_argument("--no-progress", action="store_true")
    t.set_defaults(fn=_cmd_train)


def _cmd_train(a) -> int:
    import os
    from .data.mesh_files import default_0ad_root
    from .training.train import TrainArgs, train

    if not (a.index or a.data):
        raise SystemExit("train: give --data (dataset folder or folder of meshes) or --index")
    args = TrainArgs(
        index=a.index or "",
        root=a.root or str(default_0ad_root()),
        out=a.out,
        data=a.data or "",
        config=a.config,
        steps=a.steps,
        batch_size=a.batch_size,
        micro_batch=a.micro_batch,
        lr=a.lr,
        lr_min=a.lr_min,
        warmup=a.warmup,
        seed=a.seed,
        threads=a.threads,
        device=a.device,
        precision=a.precision,
        grad_checkpoint=a.grad_checkpoint,
        fsdp=a.fsdp,
        workers=a.workers,
        init_from=a.init_from or "",
        init_config=a.init_config or "",
        log_every=a.log_every,
        val_every=a.val_every,
        val_meshes=a.val_meshes,
        ckpt_minutes=a.ckpt_minutes,
        max_minutes=a.max_minutes,
        max_cpu_minutes=a.max_cpu_minutes,
        resume=not a.no_resume,
        augment=not a.no_augment,
        max_seq_len=a.max_seq_len,
        progress=not a.no_progress,
    )
    res = train(args)
    if os.environ.get("RANK", "0") == "0":
        print(dumps(res, "null", indent=2))
    return 0


def _add_pack_checkpoint(sub) -> None:
    k = sub.add_parser(
        "pack-checkpoint",
        help="a smaller copy of a training checkpoint that still resumes "
        "(optimizer moments in bf16; the repository's resumable checkpoint)",
    )
    k.add_argument("checkpoint")
    k.add_argument("-o", "--out", required=True)
    k.add_argument("--max-bytes", type=int, default=40_000_000, help="refuse a result larger than this (0: no limit)")
    k.set_defaults(fn=_cmd_pack_checkpoint)


def _cmd_pack_checkpoint(a) -> int:
    from .checkpoint import pack_checkpoint

    try:
        print(dumps(pack_checkpoint(Path(a.checkpoint), Path(a.out), a.max_bytes), "null"))
    except (OSError, ValueError, RuntimeError, KeyError) as e:  # unreadable or not a checkpoint, too big
        print(f"silk-export pack-checkpoint: {a.checkpoint}: {e}", file=sys.stderr)
        return 2
    return 0


def _add_export(sub) -> None:
    e = sub.add_parser("export", help="checkpoint -> ONNX model folder (docs/model_contract.md)")
    e.add_argument("--checkpoint", required=True)
    add_output_arguments(e, "model")
    e.add_argument("--data", help="training data description for model.json")
    e.add_argument("--no-int8", action="store_true")
    e.add_argument("--temperature", type=float, help="model.json sampling default (absent: libsilk's, 0.5)")
    e.add_argument("--top-k", type=int, help="model.json sampling default (absent: libsilk's, 50; 0 = off)")
    e.add_argument("--top-p", type=float, help="model.json sampling default (absent: libsilk's, 1.0 = off)")
    e.add_argument(
        "--candidates",
        type=int,
        choices=range(1, 65),
        metavar="N",
        help="model.json sampling.candidates: the best of N silkgen and the C API run unless "
        "told otherwise (absent: 1)",
    )
    e.add_argument(
        "--kv-variants",
        nargs="+",
        choices=["fp16", "int8"],
        default=["fp16", "int8"],
        help="which self-K/V cache variants of every decoder to write (contract v4, files.kv_fp16 / "
        "files.kv_int8; default: both)",
    )
    e.add_argument(
        "--kv-precision",
        choices=KV_PRECISIONS,
        help="files.default_kv_precision: the cache silkgen and the C API use unless told otherwise "
        "(fp16 / int8 need that variant; absent: fp32)",
    )
    e.set_defaults(fn=_cmd_export)


def _cmd_export(a) -> int:
    from .checkpoint import model_from_checkpoint
    from .models.finite import check_finite
    from .onnx.export import export_model

    model, ck = model_from_checkpoint(Path(a.checkpoint))
    training = {
        "steps": ck["step"],
        "data": a.data or ck.get("data", {}).get("index"),
        "seed": ck.get("args", {}).get("seed"),
    }
    sampling = {
        k: v
        for k, v in (
            ("temperature", a.temperature),
            ("top_k", a.top_k),
            ("top_p", a.top_p),
            ("candidates", a.candidates),
        )
        if v is not None
    }
    try:  # NaN / Inf weights or sampling values: refused before anything is written
        check_finite(ck["model"].items(), str(a.checkpoint))
        out = output_folder(a.out, a.name)
        out.parent.mkdir(parents=True, exist_ok=True)
        meta = export_model(
            model,
            out,
            training,
            int8=not a.no_int8,
            sampling=sampling or None,
            kv_variants=tuple(dict.fromkeys(a.kv_variants)),
            kv_default=a.kv_precision,
        )
    except ValueError as e:
        print(f"silk-export export: error: {e}", file=sys.stderr)
        return 2
    print(dumps(meta, "null", indent=2))
    return 0


def _add_import_official(sub) -> None:
    from .official.hub import DEFAULT_SOURCE

    i = sub.add_parser(
        "import-official",
        help="released Mesh Silksong checkpoint (a file, or hf:ORG/NAME[@REVISION]/PATH "
        "from the model hub) -> Silk model folder (docs/model_contract.md v3)",
    )
    i.add_argument(
        "checkpoint",
        nargs="?",
        default=DEFAULT_SOURCE,
        help="model.safetensors (F32/F16/BF16) or a PyTorch state dict (.pt/.bin), or hf:ORG/NAME[@REVISION]/PATH "
        "downloaded through huggingface_hub (cached in $HF_HOME, resumed, checked against the hub's size "
        f"and SHA-256; HF_ENDPOINT, HF_TOKEN honoured); default: the released network, {DEFAULT_SOURCE}",
    )
    add_output_arguments(i, "model")
    i.add_argument(
        "--precision",
        default="auto",
        choices=["fp32", "int8", "int4", "auto"],
        help="default decoder: auto = the fastest variant that passes the fidelity check",
    )
    i.add_argument(
        "--config",
        help="JSON in the official fixture's config.json format (a file or hf:...): values no "
        "shape reveals (point_encoder.heads, point_encoder.num_points, decoder.qk_norm_scale); "
        "default: the release's (the official code's defaults)",
    )
    i.add_argument("--force", action="store_true", help="replace the model folder if it exists")
    i.add_argument("--int4-block-size", type=int, default=32)
    i.add_argument("--int4-accuracy-level", type=int, default=4)
    i.add_argument("--fidelity-tokens", type=int, default=32, help="greedy tokens per probe cloud")
    i.add_argument(
        "--kv-precision",
        default="fp16",
        choices=KV_PRECISIONS,
        help="the model's self-K/V cache precision (files.default_kv_precision; all are written)",
    )
    i.add_argument("--no-progress", action="store_true")
    i.set_defaults(fn=_cmd_import_official)


def _local_or_hub(source: str | None, progress: bool) -> tuple[Path | None, dict | None]:
    """A local path as given, or the hub file downloaded (and what the hub reported)."""
    from .official import hub

    if source is None or not hub.is_hub_source(source):
        return (Path(source) if source else None), None
    return hub.download(source, progress)


def _cmd_import_official(a) -> int:
    from .import_official import import_official
    from .official.hub import HubError
    from .official.state_dict_file import StateDictError

    try:
        out = output_folder(a.out, a.name)
        if out.exists() and not a.force:
            raise ValueError(f"{out} already exists (use --force to replace it)")
        checkpoint, hub_info = _local_or_hub(a.checkpoint, not a.no_progress)
        config, _ = _local_or_hub(a.config, not a.no_progress)
        import_official(
            checkpoint,
            out,
            a.precision,
            config,
            a.force,
            not a.no_progress,
            a.int4_block_size,
            a.int4_accuracy_level,
            a.fidelity_tokens,
            kv_precision=a.kv_precision,
            hub=hub_info,
        )
    except HubError as e:
        print(f"silk-export import-official: error: {e} (nothing was written)", file=sys.stderr)
        return 1
    except (StateDictError, ValueError, OSError) as e:
        print(f"silk-export import-official: error: {e}", file=sys.stderr)
        return 2
    return 0


def _add_kv16(sub) -> None:
    k = sub.add_parser(
        "kv16",
        help="add the fp16 self-K/V cache variant of every decoder to a model folder "
        "(docs/model_contract.md, KV precision)",
    )
    k.add_argument("folder", help="model folder (model.json + decoder*.onnx)")
    k.add_argument(
        "--default",
        choices=KV_PRECISIONS,
        help="also set files.default_kv_precision (int8 needs the kv8 variants)",
    )
    k.add_argument(
        "--attention",
        choices=["silk", "ort"],
        default="silk",
        help="silk (default): libsilk's ai.silk CachedAttention reads the float16 cache (fast; "
        "plain onnxruntime needs libsilk registered); ort: float16 casts around "
        "GroupQueryAttention (any onnxruntime, slower)",
    )
    k.add_argument(
        "--int4",
        choices=["silk", "ort"],
        help="INT4 decoders: silk (default with --attention silk): libsilk's ai.silk Int4MatMul on the same "
        "weights (reads them at memory speed); ort: keep onnxruntime's MatMulNBits",
    )
    k.set_defaults(fn=_cmd_kv16, precision="fp16")
    k8 = sub.add_parser(
        "kv8",
        help="add the int8 self-K/V cache variant (rows of D int8 + a float32 scale; "
        "libsilk's ai.silk CachedAttention) of every decoder to a model folder "
        "(docs/model_contract.md, KV precision)",
    )
    k8.add_argument("folder", help="model folder (model.json + decoder*.onnx)")
    k8.add_argument(
        "--default",
        choices=KV_PRECISIONS,
        help="also set files.default_kv_precision (fp16 needs the kv16 variants)",
    )
    k8.add_argument(
        "--int4",
        choices=["silk", "ort"],
        help="INT4 decoders: silk (default with --attention silk): libsilk's ai.silk Int4MatMul on the same "
        "weights (reads them at memory speed); ort: keep onnxruntime's MatMulNBits",
    )
    k8.set_defaults(fn=_cmd_kv16, precision="int8", attention="silk")


def _cmd_kv16(a) -> int:
    """`kv16` and `kv8`: the variants of a.precision."""
    from .onnx.kv_precision import KV_FILES, KV_SUFFIXES, add_kv_to_folder

    try:
        files = add_kv_to_folder(Path(a.folder), a.precision, a.default, a.attention, a.int4)
    except (OSError, ValueError) as e:
        print(f"silk-export {KV_SUFFIXES[a.precision]}: error: {e}", file=sys.stderr)
        return 2
    key = KV_FILES[a.precision]
    print(json.dumps({key: files[key], "default_kv_precision": files.get("default_kv_precision", "fp32")}, indent=2))
    return 0


def _report(res, out) -> int:
    """Prints a command's JSON result (non-finite numbers as null) and writes it to --out too."""
    text = dumps(res, "null", indent=2)
    if out:
        Path(out).write_text(text + "\n")
    print(text)
    return 0


def _add_eval(sub) -> None:
    v = sub.add_parser("eval", help="CD / HD / NC / |NC| and structure of generated vs reference meshes")
    v.add_argument("generated", help="mesh file or folder")
    v.add_argument("reference", nargs="?", help="mesh file or folder (same file stems)")
    v.add_argument("--points", type=int, default=10000)
    v.add_argument("--seed", type=int, default=0)
    v.add_argument("--out")
    v.set_defaults(fn=_cmd_eval)


def _cmd_eval(a) -> int:
    from .evaluation.evaluate import evaluate_paths

    res = evaluate_paths(Path(a.generated), Path(a.reference) if a.reference else None, n_points=a.points, seed=a.seed)
    return _report(res, a.out)


def _add_loss(sub) -> None:
    lo = sub.add_parser("loss", help="teacher-forced cross-entropy of a checkpoint on one split (no augmentation)")
    lo.add_argument("--checkpoint", required=True)
    lo.add_argument("--index", required=True)
    lo.add_argument("--root")
    lo.add_argument("--split", default="test")
    lo.add_argument("--limit", type=int, default=0, help="0: every mesh of the split that fits")
    lo.add_argument("--seed", type=int, default=0)
    lo.add_argument("--threads", type=int, default=1)
    lo.add_argument(
        "--no-conditioning",
        action="store_true",
        help="skip the second pass that scores each mesh's tokens with another mesh's points",
    )
    lo.add_argument("--out")
    lo.set_defaults(fn=_cmd_loss)


def _cmd_loss(a) -> int:
    from .data.mesh_files import default_0ad_root
    from .evaluation.split_loss import split_loss

    res = split_loss(
        Path(a.checkpoint),
        Path(a.index),
        Path(a.root) if a.root else default_0ad_root(),
        a.split,
        a.limit,
        a.seed,
        a.threads,
        conditioning=not a.no_conditioning,
    )
    return _report(res, a.out)


def _add_card(sub) -> None:
    c = sub.add_parser("card", help="write MODEL_CARD.md into a model folder from a training run")
    c.add_argument("--model-dir", required=True)
    c.add_argument("--run-dir", required=True)
    c.add_argument("--bench-json")
    c.set_defaults(fn=_cmd_card)


def _cmd_card(a) -> int:
    from .training.card import write_card

    path = write_card(Path(a.model_dir), Path(a.run_dir), Path(a.bench_json) if a.bench_json else None)
    print(path)
    return 0


def _add_bench(sub) -> None:
    b = sub.add_parser("bench", help="training throughput (tokens/s) per config on synthetic batches")
    b.add_argument("--configs", nargs="+", default=["micro", "tiny", "small", "paper"])
    b.add_argument("--steps", type=int, default=3)
    b.add_argument("--seq-len", type=int, default=1024)
    b.add_argument("--batch-size", type=int, default=1)
    b.add_argument("--threads", type=int, default=0)
    b.add_argument("--seed", type=int, default=0)
    b.add_argument("--out")
    b.set_defaults(fn=_cmd_bench)


def _cmd_bench(a) -> int:
    from .training.bench import bench_configs

    res = bench_configs(a.configs, a.steps, a.seq_len, a.batch_size, a.threads, a.seed)
    return _report(res, a.out)


def _add_generate(sub) -> None:
    g = sub.add_parser(
        "generate", help="generate meshes from the point clouds of input meshes with libsilk's runtime (as silkgen)"
    )
    g.add_argument(
        "--model", required=True, help="an exported model folder, or a checkpoint.pt (exported to a temporary folder)"
    )
    g.add_argument("--runtime", nargs="?", const="libsilk", help=argparse.SUPPRESS)  # before 1.2: picked libsilk
    g.add_argument("--out", required=True)
    g.add_argument("--max-tokens", type=int, default=0, help="most ids per generation (0: the model's maximum)")
    g.add_argument(
        "--temperature", type=float, help="default: the model folder's (model.json sampling), else libsilk's"
    )
    g.add_argument("--top-k", type=int, help="default: the model folder's, else libsilk's")
    g.add_argument("--top-p", type=float, help="default: the model folder's, else libsilk's")
    g.add_argument("--seed", type=int, default=0, help="silkgen --seed with the same value gives the same ids")
    g.add_argument("--threads", type=int, default=1)
    g.add_argument("--surface-tolerance", type=int, help="surface guidance in cells (default: libsilk's)")
    g.add_argument("--candidates", type=int, help="best of N (default: the model's, model.json sampling.candidates)")
    g.add_argument("--index", help="take inputs from an index (evenly spaced over one split)")
    g.add_argument("--root", help="folder the index's paths are relative to (default: 0 A.D. cache)")
    g.add_argument("--split", default="test")
    g.add_argument("--limit", type=int, default=16)
    g.add_argument("--max-index-tokens", type=int, default=2046, help="only index meshes up to this many tokens")
    g.add_argument("inputs", nargs="*")
    g.set_defaults(fn=_cmd_generate)


def _cmd_generate(a) -> int:
    from .data.mesh_files import default_0ad_root
    from .evaluation.generate import generate_paths, pick_from_index

    if a.runtime is not None:
        print("silk-export generate: note: --runtime is ignored (generation always runs libsilk)", file=sys.stderr)
    inputs = [Path(p) for p in a.inputs]
    if a.index:
        inputs += pick_from_index(
            Path(a.index), Path(a.root) if a.root else default_0ad_root(), a.split, a.limit, a.max_index_tokens
        )
    if not inputs:
        raise SystemExit("generate: no input meshes (give files or --index)")
    try:  # a missing or unreadable model, NaN weights, a model libsilk refuses
        res = generate_paths(
            Path(a.model),
            inputs,
            Path(a.out),
            a.seed,
            a.threads,
            max_tokens=a.max_tokens,
            temperature=a.temperature,
            top_k=a.top_k,
            top_p=a.top_p,
            surface_tolerance=a.surface_tolerance,
            candidates=a.candidates,
        )
    except (OSError, ValueError, RuntimeError) as e:
        print(f"silk-export generate: error: {e}", file=sys.stderr)
        return 2
    print(dumps(res, "null", indent=2))
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="silk-export", description=__doc__)
    sub = p.add_subparsers(dest="cmd", required=True)
    for add in (
        _add_dataset,
        _add_train,
        _add_pack_checkpoint,
        _add_export,
        _add_import_official,
        _add_kv16,
        _add_eval,
        _add_loss,
        _add_card,
        _add_bench,
        _add_generate,
    ):
        add(sub)
    return p


def main(argv=None) -> int:
    a = build_parser().parse_args(argv)
    return a.fn(a)


if __name__ == "__main__":
    sys.exit(main())
