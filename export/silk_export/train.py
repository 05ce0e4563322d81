"""`silk-export train`: AdamW + cosine LR over an index from `silk-export dataset`, online
augmentation and tokenization through libsilk, progressive-balanced resampling, periodic
validation, checkpoint/resume, loss log and plot. CPU or CUDA."""
from __future__ import annotations

import dataclasses
import json
import math
import random
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch
from tqdm import tqdm

from . import libsilk
from .checkpoint import load_checkpoint, save_checkpoint
from .configs import ModelConfig, config_from_dict, get_config
from .dataset_index import read_index
from .losslog import LossLog, plot_losses
from .architectures import build_model
from .resample import ProgressiveBalancedSampler
from .samples import MeshCache, TooLong, collate
from .schedule import cosine_lr

MAX_FACES = 12000


@dataclass
class TrainArgs:
    index: str
    root: str
    out: str
    config: str = "micro"
    steps: int = 1000
    batch_size: int = 4
    lr: float = 1e-4
    lr_min: float = 5e-5
    warmup: int = 0
    weight_decay: float = 0.01
    grad_clip: float = 1.0
    seed: int = 0
    threads: int = 0  # 0: leave torch's default
    device: str = "auto"
    log_every: int = 10
    val_every: int = 200
    val_meshes: int = 32
    ckpt_minutes: float = 5.0
    max_minutes: float = 0.0  # 0: no wall-clock limit
    resume: bool = True
    augment: bool = True
    max_seq_len: int = 0  # 0: the config's
    progress: bool = True
    rows_filter: dict = field(default_factory=dict)  # e.g. {"keys": [...]}: restrict training rows
    model_config: dict | None = None  # a full ModelConfig as a dict instead of a named config


def select_rows(rows: list[dict], split: str, cfg: ModelConfig, keys=None) -> list[dict]:
    out = [r for r in rows if r["split"] == split and r.get("refused") is None and r.get("tokens")
           and r["tokens"] <= cfg.max_tokens and r.get("processed_faces", 0) <= MAX_FACES]
    if keys is not None:
        keys = set(keys)
        out = [r for r in out if r["key"] in keys]
    return out


def seed_everything(seed: int) -> np.random.Generator:
    random.seed(seed)
    torch.manual_seed(seed)
    return np.random.default_rng(seed)


def draw_batch(cache: MeshCache, sampler, step, k, rng, cfg, augment, tries=50):
    out, failures = [], 0
    while len(out) < k:
        i = int(sampler.sample(step, 1, rng)[0])
        try:
            out.append(cache.sample(i, rng, cfg.max_tokens, augment=augment, n_points=cfg.n_points))
        except (TooLong, libsilk.SilkError, ValueError):
            failures += 1
            if failures > tries * k:
                raise RuntimeError("too many samples refused or too long; check the index")
    return out, failures


def fixed_val_samples(root, rows, cfg, n, seed):
    """A deterministic validation set: first n val rows, no augmentation, fixed point samples."""
    cache = MeshCache(root, rows[:n])
    rng = np.random.default_rng(seed + 1)
    out = []
    for i in range(len(cache)):
        try:
            out.append(cache.sample(i, rng, cfg.max_tokens, augment=False, n_points=cfg.n_points))
        except (TooLong, libsilk.SilkError, ValueError):
            pass
    return out


def accumulate_gradients(model, samples, device) -> tuple[float, int]:
    """Backward pass one sequence at a time (no padding work on a CPU), each scaled by its share
    of the batch's tokens: the gradient of the batch's token-mean cross-entropy. Returns
    (that mean loss, scored tokens)."""
    counts = [s.tokens.size + 1 for s in samples]  # tokens + EOS
    total = sum(counts)
    mean = 0.0
    for s, n in zip(samples, counts):
        b = collate([s])
        loss, _ = model(b["input_ids"].to(device), b["points"].to(device), b["labels"].to(device))
        (loss * (n / total)).backward()
        mean += loss.item() * n / total
    return mean, total


@torch.no_grad()
def evaluate_loss(model, samples, device) -> float:
    """Token-mean cross-entropy over fixed samples (one sequence at a time, no padding)."""
    model.eval()
    total, count = 0.0, 0
    for s in samples:
        b = collate([s])
        loss, _ = model(b["input_ids"].to(device), b["points"].to(device), b["labels"].to(device))
        total += float(loss) * (s.tokens.size + 1)
        count += s.tokens.size + 1
    model.train()
    return total / max(count, 1)


def train(a: TrainArgs) -> dict:
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if a.threads:
        torch.set_num_threads(a.threads)
    device = torch.device("cuda" if a.device == "auto" and torch.cuda.is_available() else
                          ("cpu" if a.device == "auto" else a.device))
    cfg = config_from_dict(a.model_config) if a.model_config else get_config(a.config)
    if a.max_seq_len:
        cfg = dataclasses.replace(cfg, max_seq_len=a.max_seq_len)
    rng = seed_everything(a.seed)
    rows = read_index(Path(a.index))
    train_rows = select_rows(rows, "train", cfg, a.rows_filter.get("keys"))
    val_rows = select_rows(rows, "val", cfg)
    if not train_rows:
        raise SystemExit("no training meshes in the index fit this config")
    cache = MeshCache(a.root, train_rows)
    sampler = ProgressiveBalancedSampler([r["processed_faces"] for r in train_rows], a.steps)
    val = fixed_val_samples(a.root, val_rows, cfg, a.val_meshes, a.seed) if a.val_every and val_rows else []

    model = build_model(cfg).to(device)
    opt = torch.optim.AdamW(model.parameters(), lr=a.lr, betas=(0.9, 0.99), weight_decay=a.weight_decay)
    log = LossLog(out)
    ckpt_path = out / "checkpoint.pt"
    step, elapsed0 = 0, 0.0
    if a.resume and ckpt_path.exists():
        ck = load_checkpoint(ckpt_path, map_location=device)
        model.load_state_dict(ck["model"])
        opt.load_state_dict(ck["optimizer"])
        step, elapsed0 = ck["step"], ck.get("elapsed_s", 0.0)
        rng.bit_generator.state = ck["rng"]["numpy"]
        random.setstate(ck["rng"]["python"])
        torch.set_rng_state(ck["rng"]["torch"])
        log.truncate_after(step)
    meta = {"train_meshes": len(train_rows), "val_meshes": len(val), "parameters": model.num_parameters(),
            "device": str(device), "threads": torch.get_num_threads(), "config": cfg.to_dict(),
            "args": dataclasses.asdict(a)}
    (out / "run.json").write_text(json.dumps(meta, indent=2) + "\n")

    def checkpoint(step_now, elapsed):
        save_checkpoint(ckpt_path, model, opt, step_now, {
            "elapsed_s": elapsed, "total_steps": a.steps, "args": dataclasses.asdict(a),
            "rng": {"numpy": rng.bit_generator.state, "python": random.getstate(), "torch": torch.get_rng_state()},
            "data": {"index": str(a.index), "train_meshes": len(train_rows)}})

    model.train()
    t_start = time.time()
    last_ckpt = t_start
    window_tokens, window_t = 0, time.time()
    bar = tqdm(total=a.steps, initial=step, desc=f"train {cfg.name}", unit="step", disable=not a.progress)
    first_loss = last_loss = None
    while step < a.steps:
        lr = cosine_lr(step, a.steps, a.lr, a.lr_min, a.warmup)
        for g in opt.param_groups:
            g["lr"] = lr
        samples, _ = draw_batch(cache, sampler, step, a.batch_size, rng, cfg, a.augment)
        opt.zero_grad(set_to_none=True)
        lv, n_tokens = accumulate_gradients(model, samples, device)
        if a.grad_clip:
            torch.nn.utils.clip_grad_norm_(model.parameters(), a.grad_clip)
        opt.step()
        step += 1
        if not math.isfinite(lv):
            raise RuntimeError(f"loss is {lv} at step {step}")
        first_loss = lv if first_loss is None else first_loss
        last_loss = lv
        window_tokens += n_tokens
        elapsed = elapsed0 + time.time() - t_start
        bar.update(1)
        bar.set_postfix(loss=f"{lv:.3f}", lr=f"{lr:.2e}")
        if step % a.log_every == 0 or step == a.steps:
            now = time.time()
            log.write({"step": step, "kind": "train", "loss": lv, "lr": lr, "tokens": window_tokens,
                       "tokens_per_s": window_tokens / max(now - window_t, 1e-9), "elapsed_s": elapsed})
            window_tokens, window_t = 0, now
        if val and a.val_every and (step % a.val_every == 0 or step == a.steps):
            vl = evaluate_loss(model, val, device)
            log.write({"step": step, "kind": "val", "loss": vl, "lr": lr, "elapsed_s": elapsed})
        out_of_time = a.max_minutes and elapsed0 + (time.time() - t_start) > a.max_minutes * 60 \
            and time.time() - t_start > 0
        if time.time() - last_ckpt > a.ckpt_minutes * 60 or step == a.steps or out_of_time:
            checkpoint(step, elapsed)
            last_ckpt = time.time()
            if (out / "log.jsonl").exists():
                plot_losses(out / "log.jsonl", out / "loss.png", f"{cfg.name}: step {step}")
        if out_of_time:
            break
    bar.close()
    return {"step": step, "first_loss": first_loss, "last_loss": last_loss,
            "elapsed_s": elapsed0 + time.time() - t_start, **{k: meta[k] for k in ("train_meshes", "parameters")}}
