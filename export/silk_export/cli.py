"""`silk-export` console script: dataset | train | export | eval | card, plus bench | generate | loss."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path


def _cmd_dataset(a) -> int:
    from .dataset_index import build_index
    from .mesh_files import default_0ad_root
    root = Path(a.root) if a.root else default_0ad_root()
    summary = build_index(root, Path(a.out), Path(a.dev_dir) if a.dev_dir else None, a.limit)
    print(json.dumps(summary, indent=2))
    return 0


def _cmd_train(a) -> int:
    from .train import TrainArgs, train
    from .mesh_files import default_0ad_root
    args = TrainArgs(index=a.index, root=a.root or str(default_0ad_root()), out=a.out, config=a.config,
                     steps=a.steps, batch_size=a.batch_size, lr=a.lr, lr_min=a.lr_min, warmup=a.warmup,
                     seed=a.seed, threads=a.threads, device=a.device, log_every=a.log_every,
                     val_every=a.val_every, val_meshes=a.val_meshes, ckpt_minutes=a.ckpt_minutes,
                     max_minutes=a.max_minutes, resume=not a.no_resume, augment=not a.no_augment,
                     max_seq_len=a.max_seq_len)
    print(json.dumps(train(args), indent=2))
    return 0


def _cmd_export(a) -> int:
    from .checkpoint import model_from_checkpoint
    from .onnx_export import export_model
    model, ck = model_from_checkpoint(Path(a.checkpoint))
    training = {"steps": ck["step"], "data": a.data or ck.get("data", {}).get("index"),
                "seed": ck.get("args", {}).get("seed")}
    meta = export_model(model, Path(a.out), training, int8=not a.no_int8)
    print(json.dumps(meta, indent=2))
    return 0


def _cmd_eval(a) -> int:
    from .evaluate import evaluate_paths
    res = evaluate_paths(Path(a.generated), Path(a.reference) if a.reference else None,
                         n_points=a.points, seed=a.seed)
    text = json.dumps(res, indent=2)
    if a.out:
        Path(a.out).write_text(text + "\n")
    print(text)
    return 0


def _cmd_loss(a) -> int:
    from .split_loss import split_loss
    from .mesh_files import default_0ad_root
    res = split_loss(Path(a.checkpoint), Path(a.index), Path(a.root) if a.root else default_0ad_root(),
                     a.split, a.limit, a.seed, a.threads)
    text = json.dumps(res, indent=2)
    if a.out:
        Path(a.out).write_text(text + "\n")
    print(text)
    return 0


def _cmd_card(a) -> int:
    from .card import write_card
    path = write_card(Path(a.model_dir), Path(a.run_dir), Path(a.bench_json) if a.bench_json else None)
    print(path)
    return 0


def _cmd_bench(a) -> int:
    from .bench import bench_configs
    res = bench_configs(a.configs, a.steps, a.seq_len, a.batch_size, a.threads, a.seed)
    text = json.dumps(res, indent=2)
    if a.out:
        Path(a.out).write_text(text + "\n")
    print(text)
    return 0


def _cmd_generate(a) -> int:
    from .generate import generate_paths, pick_from_index
    from .mesh_files import default_0ad_root
    inputs = [Path(p) for p in a.inputs]
    if a.index:
        inputs += pick_from_index(Path(a.index), Path(a.root) if a.root else default_0ad_root(), a.split,
                                  a.limit, a.max_index_tokens)
    if not inputs:
        raise SystemExit("generate: no input meshes (give files or --index)")
    if a.runtime:
        from .generate import generate_with_runtime
        res = generate_with_runtime(Path(a.model), inputs, Path(a.out), a.seed, a.threads, a.max_tokens,
                                    a.temperature, a.top_k)
    else:
        res = generate_paths(Path(a.model), inputs, Path(a.out), a.max_tokens,
                             a.temperature, a.top_k, a.seed, a.threads)
    print(json.dumps(res, indent=2))
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="silk-export", description=__doc__)
    sub = p.add_subparsers(dest="cmd", required=True)

    d = sub.add_parser("dataset", help="index a mesh collection through libsilk (splits, token counts)")
    d.add_argument("--root", help="0 A.D. cache ($SILK_DATA_DIR/0ad, default) or any folder of meshes")
    d.add_argument("--out", required=True, help="folder for index.jsonl and summary.json")
    d.add_argument("--dev-dir", help="dev corpus folder (default: <shared>/corpus/dev)")
    d.add_argument("--limit", type=int, help="index only the first N files (sorted)")
    d.set_defaults(fn=_cmd_dataset)

    t = sub.add_parser("train", help="train a model on an index (resumes from OUT/checkpoint.pt)")
    t.add_argument("--index", required=True)
    t.add_argument("--root", help="folder the index's `file` paths are relative to (default: 0 A.D. cache)")
    t.add_argument("--out", required=True)
    t.add_argument("--config", default="micro", choices=["micro", "tiny", "small", "paper"])
    t.add_argument("--steps", type=int, default=1000)
    t.add_argument("--batch-size", type=int, default=4)
    t.add_argument("--lr", type=float, default=1e-4)
    t.add_argument("--lr-min", type=float, default=5e-5)
    t.add_argument("--warmup", type=int, default=0)
    t.add_argument("--seed", type=int, default=0)
    t.add_argument("--threads", type=int, default=0)
    t.add_argument("--device", default="auto")
    t.add_argument("--log-every", type=int, default=10)
    t.add_argument("--val-every", type=int, default=200)
    t.add_argument("--val-meshes", type=int, default=32)
    t.add_argument("--ckpt-minutes", type=float, default=5.0)
    t.add_argument("--max-minutes", type=float, default=0.0, help="stop (and checkpoint) after this wall time")
    t.add_argument("--max-seq-len", type=int, default=0, help="override the config's max_seq_len")
    t.add_argument("--no-resume", action="store_true")
    t.add_argument("--no-augment", action="store_true")
    t.set_defaults(fn=_cmd_train)

    e = sub.add_parser("export", help="checkpoint -> ONNX model folder (docs/model_contract.md)")
    e.add_argument("--checkpoint", required=True)
    e.add_argument("--out", required=True)
    e.add_argument("--data", help="training data description for model.json")
    e.add_argument("--no-int8", action="store_true")
    e.set_defaults(fn=_cmd_export)

    v = sub.add_parser("eval", help="CD / HD / NC / |NC| and structure of generated vs reference meshes")
    v.add_argument("generated", help="mesh file or folder")
    v.add_argument("reference", nargs="?", help="mesh file or folder (same file stems)")
    v.add_argument("--points", type=int, default=10000)
    v.add_argument("--seed", type=int, default=0)
    v.add_argument("--out")
    v.set_defaults(fn=_cmd_eval)

    lo = sub.add_parser("loss", help="teacher-forced cross-entropy of a checkpoint on one split (no augmentation)")
    lo.add_argument("--checkpoint", required=True)
    lo.add_argument("--index", required=True)
    lo.add_argument("--root")
    lo.add_argument("--split", default="test")
    lo.add_argument("--limit", type=int, default=0, help="0: every mesh of the split that fits")
    lo.add_argument("--seed", type=int, default=0)
    lo.add_argument("--threads", type=int, default=1)
    lo.add_argument("--out")
    lo.set_defaults(fn=_cmd_loss)

    c = sub.add_parser("card", help="write MODEL_CARD.md into a model folder from a training run")
    c.add_argument("--model-dir", required=True)
    c.add_argument("--run-dir", required=True)
    c.add_argument("--bench-json")
    c.set_defaults(fn=_cmd_card)

    b = sub.add_parser("bench", help="training throughput (tokens/s) per config on synthetic batches")
    b.add_argument("--configs", nargs="+", default=["micro", "tiny", "small", "paper"])
    b.add_argument("--steps", type=int, default=3)
    b.add_argument("--seq-len", type=int, default=1024)
    b.add_argument("--batch-size", type=int, default=1)
    b.add_argument("--threads", type=int, default=0)
    b.add_argument("--seed", type=int, default=0)
    b.add_argument("--out")
    b.set_defaults(fn=_cmd_bench)

    g = sub.add_parser("generate", help="sample meshes from point clouds of input meshes (PyTorch, KV cache)")
    g.add_argument("--model", required=True, help="checkpoint.pt, or with --runtime an exported model folder")
    g.add_argument("--runtime", nargs="?", const="libsilk",
                   help="generate with the C++ runtime through libsilk (grammar-constrained); a value (the "
                        "former silkgen path) is accepted and ignored")
    g.add_argument("--out", required=True)
    g.add_argument("--max-tokens", type=int, default=0)
    g.add_argument("--temperature", type=float, default=0.5)
    g.add_argument("--top-k", type=int, default=50)
    g.add_argument("--seed", type=int, default=0)
    g.add_argument("--threads", type=int, default=1)
    g.add_argument("--index", help="take inputs from an index (evenly spaced over one split)")
    g.add_argument("--root", help="folder the index's paths are relative to (default: 0 A.D. cache)")
    g.add_argument("--split", default="test")
    g.add_argument("--limit", type=int, default=16)
    g.add_argument("--max-index-tokens", type=int, default=2046, help="only index meshes up to this many tokens")
    g.add_argument("inputs", nargs="*")
    g.set_defaults(fn=_cmd_generate)
    return p


def main(argv=None) -> int:
    a = build_parser().parse_args(argv)
    return a.fn(a)


if __name__ == "__main__":
    sys.exit(main())
