# SPDX-License-Identifier: MIT
"""torch.distributed for training: one process per device started by torchrun (single- or
multi-node), DistributedDataParallel or FSDP (fully_shard) around the model, rank-0-only side
effects, and full (unsharded) state dicts so checkpoints are the same file at every world size.

Without torchrun's environment (WORLD_SIZE unset or 1) nothing is initialised and every
collective is a no-op, so the same training loop runs as a plain single process."""

from __future__ import annotations

import contextlib
import os
from dataclasses import dataclass

import torch
import torch.distributed as dist


@dataclass
class DistEnv:
    rank: int = 0
    world: int = 1
    local_rank: int = 0
    device: torch.device = torch.device("cpu")
    fsdp: bool = False

    @property
    def active(self) -> bool:
        return self.world > 1

    @property
    def is_main(self) -> bool:
        return self.rank == 0

    def barrier(self) -> None:
        if self.active:
            dist.barrier()

    def all_reduce_sum(self, values: list[float]) -> list[float]:
        """Sums a few scalars over all ranks (float64 on the collective's device)."""
        if not self.active:
            return list(values)
        t = torch.tensor(values, dtype=torch.float64, device=self._collective_device())
        dist.all_reduce(t, op=dist.ReduceOp.SUM)
        return t.tolist()

    def _collective_device(self) -> torch.device:
        return self.device if dist.get_backend() == "nccl" else torch.device("cpu")

    def shutdown(self) -> None:
        if self.active and dist.is_initialized():
            dist.destroy_process_group()


def pick_device(requested: str, local_rank: int) -> torch.device:
    if requested == "auto":
        requested = "cuda" if torch.cuda.is_available() else "cpu"
    dev = torch.device(requested)
    if dev.type == "cuda" and dev.index is None:
        dev = torch.device("cuda", local_rank)
    return dev


def init_distributed(requested_device: str = "auto", fsdp: bool = False) -> DistEnv:
    """Reads torchrun's RANK / WORLD_SIZE / LOCAL_RANK (MASTER_ADDR / MASTER_PORT are read by
    init_process_group) and joins the group: NCCL on CUDA, gloo on CPU."""
    world = int(os.environ.get("WORLD_SIZE", "1"))
    rank = int(os.environ.get("RANK", "0"))
    local_rank = int(os.environ.get("LOCAL_RANK", "0"))
    device = pick_device(requested_device, local_rank)
    if device.type == "cuda":
        torch.cuda.set_device(device)
    if world > 1 and not dist.is_initialized():
        dist.init_process_group("nccl" if device.type == "cuda" else "gloo")
    return DistEnv(rank=rank, world=world, local_rank=local_rank, device=device, fsdp=fsdp)


def wrap_model(model: torch.nn.Module, env: DistEnv) -> torch.nn.Module:
    """DDP, or with env.fsdp FSDP2: each decoder/encoder layer sharded on its own, then the root.
    A single process gets the model back unchanged (env.fsdp then only checks the flag)."""
    if not env.active:
        return model
    if env.fsdp:
        from torch.distributed.device_mesh import init_device_mesh
        from torch.distributed.fsdp import fully_shard, register_fsdp_forward_method

        mesh = init_device_mesh(env.device.type, (env.world,))
        for block in shardable_blocks(model):
            fully_shard(block, mesh=mesh)
            for name in getattr(block, "fsdp_forward_methods", ()):  # called outside forward()
                register_fsdp_forward_method(block, name)
        fully_shard(model, mesh=mesh)
        return model
    from torch.nn.parallel import DistributedDataParallel

    ids = [env.device.index] if env.device.type == "cuda" else None
    return DistributedDataParallel(model, device_ids=ids)


def shardable_blocks(model: torch.nn.Module) -> list[torch.nn.Module]:
    """The repeated transformer blocks: every module of a ModuleList of 2+ layers."""
    blocks = []
    for m in model.modules():
        if isinstance(m, torch.nn.ModuleList) and len(m) > 1:
            blocks.extend(m)
    return blocks


def gradient_sync(model: torch.nn.Module, sync: bool):
    """Context for one backward: sync=False accumulates locally (gradient accumulation over
    micro-batches), sync=True reduces over ranks. DDP: no_sync(); FSDP2: set_requires_gradient_sync."""
    if hasattr(model, "no_sync") and not sync:
        return model.no_sync()
    if hasattr(model, "set_requires_gradient_sync"):
        model.set_requires_gradient_sync(sync)
    return contextlib.nullcontext()


def full_state(model: torch.nn.Module, optimizer) -> tuple[dict, dict]:
    """Unsharded CPU (model, optimizer) state dicts with the plain model's parameter names; only
    rank 0 gets them under FSDP (others get empty dicts). The same layout at every world size."""
    from torch.distributed.checkpoint.state_dict import StateDictOptions, get_state_dict

    opts = StateDictOptions(full_state_dict=True, cpu_offload=True)
    return get_state_dict(model, optimizer, options=opts)


def load_full_state(model: torch.nn.Module, optimizer, model_state: dict, optim_state: dict | None) -> None:
    """Loads full_state()'s dicts (every rank passes the whole dicts) into a wrapped model."""
    from torch.distributed.checkpoint.state_dict import StateDictOptions, set_state_dict

    opts = StateDictOptions(full_state_dict=True)
    if optim_state is None:
        set_state_dict(model, [], model_state_dict=model_state, optim_state_dict={}, options=opts)
    else:
        set_state_dict(model, optimizer, model_state_dict=model_state, optim_state_dict=optim_state, options=opts)
