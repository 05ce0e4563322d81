# SPDX-License-Identifier: MIT
"""Token ids for the model, read from the vocabulary layout (engine/tokenizer/vocabulary_layout.json, the
single source, shipped inside this package: paths.vocabulary_layout_text).

Adds the model-only BOS id and the type-embedding classes of token_format.md §9 / docs/model_contract.md."""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .paths import vocabulary_layout_text

# Type-embedding classes (token_format.md §9): index 0 = no type vector (C, U, E, EOS, PAD, BOS).
TYPE_CLASSES = ("X", "S", "B", "K", "O")


@dataclass(frozen=True)
class Vocab:
    layout: dict
    format_vocab_size: int
    eos_id: int
    pad_id: int
    bos_id: int
    model_vocab_size: int  # logits: format ids + EOS + PAD
    embedding_rows: int  # + BOS
    max_seq_length: int  # tokenizer-side limit (tokens incl. EOS)

    def type_of_id(self) -> np.ndarray:
        """int64 [embedding_rows]: 0 for no type, 1 + index in TYPE_CLASSES otherwise."""
        out = np.zeros(self.embedding_rows, dtype=np.int64)
        for k, name in enumerate(TYPE_CLASSES):
            lo, hi = self.layout["ranges"][name]
            out[lo:hi] = k + 1
        return out

    def sidecar(self) -> dict:
        return {
            "format_vocab_size": self.format_vocab_size,
            "eos_id": self.eos_id,
            "pad_id": self.pad_id,
            "bos_id": self.bos_id,
            "model_vocab_size": self.model_vocab_size,
            "embedding_rows": self.embedding_rows,
        }


@lru_cache(maxsize=1)
def load_vocab() -> Vocab:
    layout = json.loads(vocabulary_layout_text())
    eos, pad = int(layout["eos_id"]), int(layout["pad_id"])
    model_vocab = int(layout["model_vocab_size"])
    assert model_vocab == pad + 1, "layout: model_vocab_size must be pad_id + 1"
    bos = model_vocab  # the contract's BOS: first id after the output vocabulary
    return Vocab(
        layout=layout,
        format_vocab_size=int(layout["format_vocab_size"]),
        eos_id=eos,
        pad_id=pad,
        bos_id=bos,
        model_vocab_size=model_vocab,
        embedding_rows=bos + 1,
        max_seq_length=int(layout["max_seq_length"]),
    )
