# SPDX-License-Identifier: MIT
"""Training log: JSONL (every record) + CSV (step, kind, loss, lr, tokens/s, elapsed) and a PNG
plot of train/val loss (matplotlib, Agg backend, no display needed)."""

from __future__ import annotations

import csv
import json
from pathlib import Path

from ..json_io import jsonl_line

CSV_FIELDS = ["step", "kind", "loss", "lr", "tokens", "tokens_per_s", "elapsed_s"]


class LossLog:
    def __init__(self, out_dir: Path):
        self.jsonl = Path(out_dir) / "log.jsonl"
        self.csv = Path(out_dir) / "loss.csv"
        if not self.csv.exists():
            with open(self.csv, "w", newline="") as fh:
                csv.writer(fh).writerow(CSV_FIELDS)

    def write(self, record: dict) -> None:
        with open(self.jsonl, "a") as fh:
            fh.write(jsonl_line(record, "null"))
        with open(self.csv, "a", newline="") as fh:
            csv.writer(fh).writerow([record.get(k, "") for k in CSV_FIELDS])

    def truncate_after(self, step: int) -> None:
        """On resume: drop records past the checkpoint's step (they will be redone)."""
        if self.jsonl.exists():
            keep = [r for r in read_log(self.jsonl) if r["step"] <= step]
            self.jsonl.write_text("".join(jsonl_line(r, "null") for r in keep))
            with open(self.csv, "w", newline="") as fh:
                w = csv.writer(fh)
                w.writerow(CSV_FIELDS)
                for r in keep:
                    w.writerow([r.get(k, "") for k in CSV_FIELDS])


def read_log(path: Path) -> list[dict]:
    with open(path) as fh:
        return [json.loads(line) for line in fh if line.strip()]


def plot_losses(log_path: Path, png_path: Path, title: str = "") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    recs = read_log(log_path)
    tr = [(r["step"], r["loss"]) for r in recs if r["kind"] == "train"]
    va = [(r["step"], r["loss"]) for r in recs if r["kind"] == "val"]
    fig, ax = plt.subplots(figsize=(7, 4), dpi=110)
    if tr:
        s, l = zip(*tr)
        ax.plot(s, l, lw=0.6, alpha=0.35, color="tab:blue")
        k = max(3, len(l) // 20)
        sm = [sum(l[max(0, i - k + 1) : i + 1]) / len(l[max(0, i - k + 1) : i + 1]) for i in range(len(l))]
        ax.plot(s, sm, lw=1.5, color="tab:blue", label="train (moving mean)")
    if va:
        s, l = zip(*va)
        ax.plot(s, l, "o-", ms=3, color="tab:orange", label="val")
    ax.set_xlabel("step")
    ax.set_ylabel("cross-entropy (nats/token)")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(png_path)
    plt.close(fig)
