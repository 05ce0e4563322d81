# SPDX-License-Identifier: MIT
"""MODEL_CARD.md for an imported official checkpoint: where the weights came from (file name,
SHA-256, licence), what the importer checked, and each decoder variant's measured fidelity."""

from __future__ import annotations

from pathlib import Path


def write_official_card(folder: Path, meta: dict) -> Path:
    src, imp, dims, files = meta["source"], meta["import"], meta["dims"], meta["files"]
    load = imp["load"]
    L = ["# Model card: the released Mesh Silksong network, imported", ""]
    L += [
        "Written by `silk-export import-official` from the checkpoint below; the network is the",
        "official one (`arch: official` in model.json), re-implemented from",
        "`official-model/ARCHITECTURE.md` and exported per `docs/model_contract.md` (version 3).",
        "",
    ]
    L += [
        "## Source",
        "",
        "| | |",
        "|---|---|",
        f"| file | `{src['file']}` |",
        f"| bytes | {src['bytes']:,} |",
        f"| SHA-256 | `{src['sha256']}` |",
        f"| licence | {src['licence']} |",
        f"| tensors in the file | {load['tensors']} (dtypes of the used ones: {load['source_dtypes']}) |",
        f"| used at inference | {load['used']} tensors, {load['parameters']:,} parameters |",
        f"| skipped (training-only point-encoder parts) | {load['skipped_unused']} |",
        f"| wrapper prefixes stripped | {load['stripped_prefixes'] or 'none'} |",
        "",
    ]
    L += ["## Architecture (read from the tensor shapes)", "", "| | |", "|---|---|"]
    L += [f"| {k} | {v} |" for k, v in dims.items()]
    L += [
        "",
        "## What was verified",
        "",
        "* Every tensor the network uses was present with the expected shape; no unknown key",
        "  (the import stops with an error naming the key otherwise).",
        "* The re-implementation and its exported fp32 graphs match the official implementation's",
        "  outputs on `official-fixture/` within 1e-4 (context, teacher-forced logits, 100 greedy",
        "  ids): `python3 -m pytest export/tests/test_official.py`.",
        "* Each decoder variant against the fp32 one, teacher-forced on the fp32 model's own greedy",
        f"  sequences from two probe point clouds (pass: top-1 >= {imp['thresholds']['min_top1']},",
        f"  mean KL <= {imp['thresholds']['max_kl_mean']}):",
        "",
        "| decoder | file | top-1 agreement | mean KL | max KL | ms/token (1 thread, import machine) |",
        "|---|---|---|---|---|---|",
    ]
    for name, f in imp["fidelity"].items():
        L.append(
            f"| {name} | `{f['file']}` | {f['top1_agreement']:.4f} | {f['kl_mean']:.3g} | {f['kl_max']:.3g} "
            f"| {f['ms_per_token']} |"
        )
    L += [
        "",
        f"Default decoder (`files.default_decoder`): **{files['default_decoder']}** "
        f"(precision `{imp['precision']}`; INT4 block size {imp['int4']['block_size']}, "
        f"accuracy level {imp['int4']['accuracy_level']}).",
        "",
        "Pre-processing and sampling defaults (model.json): the official ones, official_network.md §4.",
        "",
    ]
    path = Path(folder) / "MODEL_CARD.md"
    path.write_text("\n".join(L))
    return path
