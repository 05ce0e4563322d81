# SPDX-License-Identifier: MIT
"""`silk-export train` and what it needs: the training loop, the per-rank sample stream,
learning-rate schedule, torch.distributed (DDP / FSDP), the loss log, and the model card and
throughput bench written from a run."""
