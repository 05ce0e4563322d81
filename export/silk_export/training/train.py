# SPDX-License-Identifier: MIT
"""`silk-export train`: AdamW + cosine LR over a dataset (sharded cache, a folder of meshes, or an
index of mesh files), online augmentation and tokenization through libsilk, progressive-balanced
resampling, periodic validation, checkpoint/resume, loss log and plot. CPU or CUDA, one process
or many under torchrun (DDP, or FSDP with --fsdp; distributed.py)."""

from __future__ import annotations

import contextlib
import dataclasses
import math
import random
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch
from tqdm import tqdm

import silk_mesh
from ..data.dataset_index import build_index, read_index
from ..data.resample import ProgressiveBalancedSampler
from ..data.samples import MeshCache, TooLong, collate
from ..data.sharded_dataset import ShardedSource, dataset_rows, is_dataset
from ..json_io import write_json
from ..checkpoint import load_checkpoint, save_state
from ..models.configs import ModelConfig, config_from_dict, get_config
from ..registry import build_model as architecture_model
from ..registry import get_architecture
from .distributed import DistEnv, full_state, gradient_sync, init_distributed, load_full_state, wrap_model
from .losslog import LossLog, plot_losses
from .schedule import cosine_lr
from .train_data import StepSamples, rank_slots, step_loader

MAX_FACES = 12000
LR_DEFAULTS = {"scratch": (1e-4, 5e-5), "finetune": (2e-5, 2e-6)}  # (peak, final)


@dataclass
class TrainArgs:
    index: str = ""  # index.jsonl of mesh files under `root` (or use `data`)
    root: str = ""
    out: str = ""
    data: str = ""  # a dataset folder (dataset.json + shards) or any folder of meshes
    config: str = "micro"
    steps: int = 1000
    batch_size: int = 4  # global: sequences per optimizer step over all ranks
    micro_batch: int = 0  # sequences per forward/backward (rest accumulated); 0: 1 on CPU, all on CUDA
    lr: float | None = None  # None: 1e-4, or 2e-5 when fine-tuning (init_from)
    lr_min: float | None = None  # None: 5e-5, or 2e-6 when fine-tuning
    warmup: int | None = None  # None: 0, or min(200, steps // 10) when fine-tuning
    weight_decay: float = 0.01
    grad_clip: float = 1.0
    seed: int = 0
    threads: int = 0  # 0: leave torch's default
    device: str = "auto"
    precision: str = "auto"  # auto (bf16 autocast on CUDA, fp32 on CPU) | fp32 | bf16
    grad_checkpoint: bool = False
    fsdp: bool = False
    workers: int = 0  # DataLoader worker processes per rank
    init_from: str = ""  # released-format checkpoint to fine-tune (official architecture)
    init_config: str = ""  # its config.json (official fixture format) for values no shape reveals
    log_every: int = 10
    val_every: int = 200
    val_meshes: int = 32
    ckpt_minutes: float = 5.0
    max_minutes: float = 0.0  # wall-clock limit of this invocation (a resumed run gets it anew); 0: none
    max_cpu_minutes: float = 0.0  # CPU-time limit of this invocation (this process, all its threads); 0: none
    resume: bool = True
    augment: bool = True
    max_seq_len: int = 0  # 0: the config's
    progress: bool = True
    rows_filter: dict = field(default_factory=dict)  # e.g. {"keys": [...]}: restrict training rows
    model_config: dict | None = None  # a full ModelConfig as a dict instead of a named config

    def schedule(self) -> tuple[float, float, int]:
        """(peak LR, final LR, warm-up steps) with the defaults of this kind of run filled in."""
        kind = "finetune" if self.init_from else "scratch"
        lr = self.lr if self.lr is not None else LR_DEFAULTS[kind][0]
        lr_min = self.lr_min if self.lr_min is not None else LR_DEFAULTS[kind][1]
        warm = self.warmup if self.warmup is not None else (min(200, self.steps // 10) if self.init_from else 0)
        return lr, lr_min, warm


def resolved_args(a: TrainArgs) -> dict:
    """The run's arguments as recorded (run.json, checkpoint), LR defaults filled in."""
    lr, lr_min, warmup = a.schedule()
    return {**dataclasses.asdict(a), "lr": lr, "lr_min": lr_min, "warmup": warmup}


def select_rows(rows: list[dict], split: str, cfg: ModelConfig, keys=None) -> list[dict]:
    out = [
        r
        for r in rows
        if r["split"] == split
        and r.get("refused") is None
        and r.get("tokens")
        and r["tokens"] <= cfg.max_tokens
        and r.get("processed_faces", 0) <= MAX_FACES
    ]
    if keys is not None:
        keys = set(keys)
        out = [r for r in out if r["key"] in keys]
    return out


def seed_everything(seed: int) -> np.random.Generator:
    random.seed(seed)
    torch.manual_seed(seed)
    return np.random.default_rng(seed)


def val_samples(source, cfg, n, seed):
    """A deterministic validation set: first n rows of `source`, no augmentation, fixed points."""
    rng = np.random.default_rng(seed + 1)
    out = []
    for i in range(min(n, len(source))):
        try:
            out.append(source.sample(i, rng, cfg.max_tokens, augment=False, n_points=cfg.n_points))
        except (TooLong, silk_mesh.SilkError, ValueError):
            pass
    return out


def fixed_val_samples(root, rows, cfg, n, seed):
    return val_samples(MeshCache(root, rows[:n]), cfg, n, seed)


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


@torch.no_grad()
def distributed_loss(model, samples, env: DistEnv, amp) -> float:
    """evaluate_loss over all ranks: rank r scores samples r, r + W, ...; ranks with one fewer
    run a padding forward that is not counted (FSDP needs the same number of forwards)."""
    per = -(-len(samples) // env.world)
    mine = samples[env.rank :: env.world]
    model.eval()
    total = count = 0.0
    for k, s in enumerate(mine + samples[:1] * (per - len(mine))):
        b = collate([s])
        with amp():
            loss, _ = model(*(b[x].to(env.device) for x in ("input_ids", "points", "labels")))
        if k < len(mine):
            total, count = total + float(loss) * b["n_tokens"], count + b["n_tokens"]
    model.train()
    total, count = env.all_reduce_sum([total, count])
    return total / max(count, 1)


def train_step(model, opt, samples, env: DistEnv, micro: int, amp, grad_clip: float) -> tuple[float, float]:
    """One optimizer step on this rank's samples, in micro-batches of `micro` sequences with
    gradients accumulated; each micro-batch's loss is weighted by its share of the global batch's
    tokens (× world, since DDP/FSDP average over ranks), so the update is that of the global
    batch's token-mean cross-entropy at any world size. Returns (this rank's token-weighted loss
    sum, global token count)."""
    n_global = env.all_reduce_sum([sum(s.tokens.size + 1 for s in samples)])[0]
    chunks = [samples[i : i + micro] for i in range(0, len(samples), micro)]
    opt.zero_grad(set_to_none=True)
    loss_sum = 0.0
    for k, chunk in enumerate(chunks):
        b = collate(chunk)
        with gradient_sync(model, k == len(chunks) - 1):
            with amp():
                loss, _ = model(*(b[x].to(env.device) for x in ("input_ids", "points", "labels")))
            (loss * (b["n_tokens"] / n_global * env.world)).backward()
        loss_sum += loss.item() * b["n_tokens"]
    if grad_clip:
        torch.nn.utils.clip_grad_norm_(model.parameters(), grad_clip)
    opt.step()
    return loss_sum, n_global


def autocast_for(device: torch.device, precision: str):
    if precision == "auto":
        precision = "bf16" if device.type == "cuda" else "fp32"
    if precision == "bf16":
        return lambda: torch.autocast(device.type, dtype=torch.bfloat16)
    if precision != "fp32":
        raise ValueError(f"--precision {precision}: expected auto, fp32 or bf16")
    return contextlib.nullcontext


@dataclass
class TrainingData:
    train: object  # a source with rows / sample() (MeshCache or ShardedSource)
    val: object | None
    description: str


def open_data(a: TrainArgs, env: DistEnv, cfg: ModelConfig, out: Path) -> TrainingData:
    """--data DATASET (dataset.json), --data FOLDER (rank 0 caches it under OUT/data first, every
    mesh as training data), or --index with --root. Point clouds follow the architecture's
    pre-processing (official: merge, 50 K surface samples, float16 rounding, draw)."""
    kind = get_architecture(cfg.arch).points_kind(cfg)
    if a.data:
        path = Path(a.data)
        if not is_dataset(path) and (path / "index.jsonl").is_file():
            raise SystemExit(
                f"--data {path}: an index without dataset.json (an older `silk-export dataset`); "
                "rebuild it, or pass it as --index with --root"
            )
        if not is_dataset(path):
            path = out / "data"
            if env.is_main and not is_dataset(path):
                build_index(Path(a.data), path, all_train=True)
            env.barrier()
        rows = dataset_rows(path)
        make = lambda rs: ShardedSource(path, rs, kind)  # noqa: E731
        desc = str(a.data)
    else:
        rows = read_index(Path(a.index))
        make = lambda rs: MeshCache(a.root, rs, kind)  # noqa: E731
        desc = str(a.index)
    train_rows = select_rows(rows, "train", cfg, a.rows_filter.get("keys"))
    if not train_rows:
        raise SystemExit("no training meshes in the data fit this config")
    val_rows = select_rows(rows, "val", cfg)
    return TrainingData(make(train_rows), make(val_rows[: a.val_meshes]) if val_rows else None, desc)


def model_config(a: TrainArgs) -> ModelConfig:
    cfg = config_from_dict(a.model_config) if a.model_config else get_config(a.config)
    return dataclasses.replace(cfg, max_seq_len=a.max_seq_len) if a.max_seq_len else cfg


def freeze_unused(model) -> None:
    """Parameters no forward reaches (e.g. the context norm of the point encoder's self-attention
    blocks) get requires_grad=False, found by one backward on a 2-token dummy sequence: DDP then
    needs no unused-parameter search, and the optimizer state covers every trained parameter."""
    ids = torch.tensor([[model.bos_id, 0]])
    labels = torch.tensor([[0, model.eos_id]])
    loss, _ = model(ids, torch.zeros(1, model.cfg.n_points, 6), labels)
    loss.backward()
    for p in model.parameters():
        if p.grad is None:
            p.requires_grad_(False)
    model.zero_grad(set_to_none=True)


def initial_model(a: TrainArgs, env: DistEnv):
    """A fresh model of the run's config, or with --init-from the released-format checkpoint
    loaded through the importer (official architecture; its config comes from the weights)."""
    if not a.init_from:
        torch.manual_seed(a.seed)  # the same initial weights on every rank
        return architecture_model(model_config(a))
    from ..official.checkpoint import load_official

    model, _ = load_official(
        Path(a.init_from), Path(a.init_config) if a.init_config else None, progress=a.progress and env.is_main
    )
    if a.max_seq_len and a.max_seq_len != model.cfg.max_seq_len:
        raise SystemExit(f"--max-seq-len: the checkpoint's positions fix it at {model.cfg.max_seq_len}")
    return model


def build_model(a: TrainArgs, env: DistEnv):
    """(wrapped model for training, the plain module, optimizer)."""
    plain = initial_model(a, env)
    freeze_unused(plain)
    plain.gradient_checkpointing = a.grad_checkpoint
    plain.to(env.device)
    model = wrap_model(plain, env)
    lr, _, _ = a.schedule()
    opt = torch.optim.AdamW(
        [p for p in model.parameters() if p.requires_grad], lr=lr, betas=(0.9, 0.99), weight_decay=a.weight_decay
    )
    return model, plain, opt


def train(a: TrainArgs) -> dict:
    env = init_distributed(a.device, a.fsdp)
    try:
        return Trainer(a, env).run()
    finally:
        env.shutdown()


class Trainer:
    def __init__(self, a: TrainArgs, env: DistEnv):
        self.a, self.env = a, env
        self.out = Path(a.out)
        self.out.mkdir(parents=True, exist_ok=True)
        if a.threads:
            torch.set_num_threads(a.threads)
        seed_everything(a.seed)
        self.model, self.plain, self.opt = build_model(a, env)
        self.cfg = self.plain.cfg
        self.data = open_data(a, env, self.cfg, self.out)
        self.amp = autocast_for(env.device, a.precision)
        self.micro = a.micro_batch or (1 if env.device.type == "cpu" else a.batch_size // env.world)
        self.slots = rank_slots(a.batch_size, env.rank, env.world)
        self.val = (
            val_samples(self.data.val, self.cfg, a.val_meshes, a.seed)
            if a.val_every and self.data.val is not None
            else []
        )
        self.ckpt_path = self.out / "checkpoint.pt"
        self.step, self.elapsed0 = self.resume()
        self.log = LossLog(self.out) if env.is_main else None
        if self.log and self.step:
            self.log.truncate_after(self.step)
        self.meta = {
            "train_meshes": len(self.data.train),
            "val_meshes": len(self.val),
            "parameters": self.plain.num_parameters(),
            "device": str(env.device),
            "world_size": env.world,
            "fsdp": a.fsdp,
            "threads": torch.get_num_threads(),
            "config": self.cfg.to_dict(),
            "args": resolved_args(a),
        }
        if env.is_main:
            write_json(self.out / "run.json", self.meta, "null")

    def resume(self) -> tuple[int, float]:
        if not (self.a.resume and self.ckpt_path.exists()):
            return 0, 0.0
        ck = load_checkpoint(self.ckpt_path)  # every rank reads it (OUT on a shared filesystem)
        load_full_state(self.model, self.opt, ck["model"], ck["optimizer"])
        return ck["step"], ck.get("elapsed_s", 0.0)

    def checkpoint(self, step: int, elapsed: float) -> None:
        model_state, optim_state = full_state(self.model, self.opt)  # a collective under FSDP
        if self.env.is_main:
            save_state(
                self.ckpt_path,
                self.cfg.to_dict(),
                model_state,
                optim_state,
                step,
                {
                    "elapsed_s": elapsed,
                    "total_steps": self.a.steps,
                    "args": resolved_args(self.a),
                    "world_size": self.env.world,
                    "data": {"index": self.data.description, "train_meshes": len(self.data.train)},
                },
            )
            if (self.out / "log.jsonl").exists():
                plot_losses(self.out / "log.jsonl", self.out / "loss.png", f"{self.cfg.name}: step {step}")

    def run(self) -> dict:
        a, env = self.a, self.env
        lr_max, lr_min, warm = a.schedule()
        sampler = ProgressiveBalancedSampler([r["processed_faces"] for r in self.data.train.rows], a.steps)
        batches = iter(
            step_loader(
                StepSamples(self.data.train, sampler, a.seed, self.cfg, a.augment, self.slots, a.steps),
                self.step,
                a.workers,
            )
        )
        step, t_start, cpu_start = self.step, time.time(), time.process_time()
        last_ckpt, window_tokens, window_t = t_start, 0, t_start
        bar = tqdm(
            total=a.steps,
            initial=step,
            desc=f"train {self.cfg.name}",
            unit="step",
            disable=not (a.progress and env.is_main),
        )
        first_loss = last_loss = None
        self.model.train()
        while step < a.steps:
            lr = cosine_lr(step, a.steps, lr_max, lr_min, warm)
            for g in self.opt.param_groups:
                g["lr"] = lr
            loss_sum, n_tokens = train_step(self.model, self.opt, next(batches), env, self.micro, self.amp, a.grad_clip)
            step += 1
            now = time.time()
            out_of_time = (bool(a.max_minutes) and now - t_start > a.max_minutes * 60) or (
                bool(a.max_cpu_minutes) and time.process_time() - cpu_start > a.max_cpu_minutes * 60
            )
            ckpt_due = now - last_ckpt > a.ckpt_minutes * 60
            loss_sum, out_of_time, ckpt_due = env.all_reduce_sum([loss_sum, out_of_time, ckpt_due])
            lv = loss_sum / n_tokens
            if not math.isfinite(lv):
                raise RuntimeError(f"loss is {lv} at step {step}")
            first_loss = lv if first_loss is None else first_loss
            last_loss, window_tokens = lv, window_tokens + n_tokens
            elapsed = self.elapsed0 + now - t_start
            bar.update(1)
            bar.set_postfix(loss=f"{lv:.3f}", lr=f"{lr:.2e}")
            if self.log and (step % a.log_every == 0 or step == a.steps):
                self.log.write(
                    {
                        "step": step,
                        "kind": "train",
                        "loss": lv,
                        "lr": lr,
                        "tokens": int(window_tokens),
                        "tokens_per_s": window_tokens / max(now - window_t, 1e-9),
                        "elapsed_s": elapsed,
                    }
                )
                window_tokens, window_t = 0, now
            if self.val and a.val_every and (step % a.val_every == 0 or step == a.steps):
                vl = distributed_loss(self.model, self.val, env, self.amp)
                if self.log:
                    self.log.write({"step": step, "kind": "val", "loss": vl, "lr": lr, "elapsed_s": elapsed})
            if ckpt_due or step == a.steps or out_of_time:
                self.checkpoint(step, elapsed)
                last_ckpt = time.time()
            if out_of_time:
                break
        bar.close()
        return {
            "step": step,
            "first_loss": first_loss,
            "last_loss": last_loss,
            "world_size": env.world,
            "elapsed_s": self.elapsed0 + time.time() - t_start,
            **{k: self.meta[k] for k in ("train_meshes", "parameters")},
        }
