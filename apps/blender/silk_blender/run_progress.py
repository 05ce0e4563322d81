# SPDX-License-Identifier: GPL-3.0-or-later
"""Where a step-wise generation is, for the sidebar's progress bar: the candidate and ids so far (the
generator's stats after each advance; no per-id Python callback, which would cost the modal run its
speed) and the layer in progress (advance(until_layer=True) returns at each completed layer), and
afterwards the candidates' scores (the run's JSON report). Kept in the window manager's silk_run
(sidebar.SilkRunState) so the panel draws it and a script can read it."""

from __future__ import annotations

import json


class RunProgress:
    def __init__(self, settings, max_tokens: int):
        self.settings = settings  # the window manager's SilkRunState, or None (no sidebar registered)
        self.max_tokens = max(1, max_tokens)  # the run's cap on ids per candidate
        self.last = {}  # candidate, candidates, tokens of the latest stats
        self.candidate, self.layers_done, self._tokens = -1, 0, 0
        self.counts = None  # (running, done, N) of best of N's candidates, when the modal run shows them

    def after_candidates(self, views: list[dict]) -> None:
        """The candidates' views (silk_mesh Generator.candidates()): how many run and how many are done."""
        running = sum(c["state"] == "running" for c in views)
        done = sum(c["state"] in ("ended", "scored") for c in views)
        self.counts = (running, done, len(views))

    def after_advance(self, stats: dict, max_ids: int, done: bool) -> None:
        """After each advance(max_ids, until_layer=True): fewer ids than asked and not done means a layer
        ended (a layer ending exactly at max_ids is counted at the next one). publish() shows it."""
        self.last = p = {
            "candidate": stats["chosen_candidate"],
            "candidates": stats["candidates"],
            "tokens": stats["tokens"],
            "max_tokens": self.max_tokens,
        }
        cand, tokens = p["candidate"], p["tokens"]
        if cand != self.candidate:
            self.candidate, self.layers_done, self._tokens = cand, 0, 0
        elif not done and tokens - self._tokens < max_ids:
            self.layers_done += 1
        self._tokens = tokens

    def fraction(self) -> float:
        p = self.last
        n, cap = max(1, p.get("candidates", 1)), max(1, p.get("max_tokens", 1))
        return min(1.0, (max(0, self.candidate) + min(1.0, p.get("tokens", 0) / cap)) / n)

    def text(self) -> str:
        p = self.last
        if not p:
            return "preparing the points (encoder)"
        rows = ""
        if self.counts and self.counts[2] > 1:  # "; " separates the sidebar's candidates line
            rows = f"candidates running {self.counts[0]}, done {self.counts[1]} of {self.counts[2]}; "
        return rows + (
            f"candidate {max(0, self.candidate) + 1} of {p.get('candidates', 1)}, layer {self.layers_done + 1}, "
            f"{p.get('tokens', 0)} / {p.get('max_tokens', 0)} ids"
        )

    def publish(self, done: bool = False) -> None:
        """Into the run state, once per UI tick, only what changed."""
        s = self.settings
        if s is None:
            return
        running, progress, status = not done, 1.0 if done else self.fraction(), self.text()
        if s.running != running:
            s.running = running
        if abs(s.progress - progress) > 1e-4:
            s.progress = progress
        if s.status != status:
            s.status = status

    def finish(self, report_json: str, chosen: int, outcome: str = "done") -> None:
        """The candidates' scores from the finished run's report (index, seed, score, faces); outcome: done,
        cancelled or failed."""
        s = self.settings
        if s is None:
            return
        s.running, s.progress = False, 1.0
        s.scores.clear()
        for c in json.loads(report_json).get("candidates", []):
            row = s.scores.add()
            row.index, row.seed, row.faces = c["index"], str(c["seed"]), c["faces"]
            row.score = c["score"] if c["score"] is not None else -1.0
            row.chosen = c["index"] == chosen
        s.status = f"{outcome}: {self.text()}"
