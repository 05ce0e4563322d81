# SPDX-License-Identifier: MIT
"""The released checkpoint from the model hub in one step: `hf:ORG/NAME[@REVISION]/PATH` is fetched
through huggingface_hub (its cache under $HF_HOME, resumed after an interruption, a progress bar,
$HF_ENDPOINT and $HF_TOKEN honoured), then checked against the size and SHA-256 the hub reports
before import-official reads it. Every failure is a HubError naming the file's hub URL and what went
wrong; a download that fails its check is removed from the cache, so a rerun fetches it again."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

# The authors' release (github.com/gaochao-s/Mesh-Silksong README, "Checkpoints Download"). The
# release has no config file of its own: its settings are the official code's defaults
# (config/options.py, miche/shapevae-256.yaml), which official_config() already holds.
DEFAULT_SOURCE = "hf:gcsong/mesh_silksong/release-100K/model.safetensors"
_SOURCE = re.compile(r"^hf:(?P<repo>[A-Za-z0-9][\w.-]*/[A-Za-z0-9][\w.-]*)(?:@(?P<rev>[^/@]+))?/(?P<path>[^@]+)$")
_SHA256 = re.compile(r"^[0-9a-f]{64}$")


class HubError(Exception):
    """A hub download that failed: the message names the URL and the reason."""


@dataclass(frozen=True)
class HubSource:
    repo_id: str
    revision: str
    filename: str

    def url(self) -> str:
        from huggingface_hub import hf_hub_url

        return hf_hub_url(self.repo_id, self.filename, revision=self.revision)

    def __str__(self) -> str:
        return f"hf:{self.repo_id}@{self.revision}/{self.filename}"


def is_hub_source(text: str) -> bool:
    return str(text).startswith("hf:")


def parse_source(text: str) -> HubSource:
    """hf:ORG/NAME[@REVISION]/PATH (REVISION: a branch, tag or commit; default main)."""
    m = _SOURCE.match(text)
    if not m or ".." in m["path"].split("/") or m["path"].startswith("/"):
        raise HubError(f"'{text}' is not a hub source: expected hf:ORG/NAME[@REVISION]/PATH, e.g. {DEFAULT_SOURCE}")
    return HubSource(m["repo"], m["rev"] or "main", m["path"])


def _hub():
    try:
        import huggingface_hub
    except ImportError as e:
        raise HubError("downloading from the hub needs huggingface_hub: pip install 'silk-mesh[train]'") from e
    return huggingface_hub


def _reason(e: BaseException, src: HubSource) -> str:
    """What failed, in the user's terms (huggingface_hub's error classes)."""
    from huggingface_hub import errors

    if isinstance(e, errors.RevisionNotFoundError):
        return f"revision '{src.revision}' not found in {src.repo_id}"
    if isinstance(e, errors.RepositoryNotFoundError):
        return f"repository '{src.repo_id}' not found (a private or gated one needs HF_TOKEN)"
    if isinstance(e, errors.RemoteEntryNotFoundError):
        return f"file '{src.filename}' not found in {src.repo_id}@{src.revision}"
    if isinstance(e, errors.HfHubHTTPError):
        status = getattr(getattr(e, "response", None), "status_code", "?")
        return f"HTTP {status}: {str(e).splitlines()[0]}"
    if isinstance(e, errors.LocalEntryNotFoundError):
        cause = e.__cause__ or e.__context__
        return (
            "cannot reach the hub and no copy is cached"
            + (f" ({type(cause).__name__}: {cause})" if cause else "")
            + "; check HF_ENDPOINT and the network"
        )
    text = str(e).splitlines()[0] if str(e) else type(e).__name__
    kind = type(e).__name__
    if kind in ("RemoteProtocolError", "ReadTimeout", "ReadError") or "Consistency check failed" in text:
        return f"download interrupted ({kind}: {text}); run the command again to resume it"
    if kind in ("ConnectError", "ConnectTimeout"):
        return f"cannot connect ({text}); check HF_ENDPOINT and the network"
    return f"{kind}: {text}"


def _forget(path: Path) -> None:
    """Removes a cached file (its snapshot link and the blob), so the next run downloads it again."""
    blob = path.resolve()
    for p in (path, blob):
        try:
            p.unlink()
        except FileNotFoundError:
            pass


def _check(path: Path, src: HubSource, url: str, size: int | None, etag: str | None) -> str:
    """The cached file against the hub's size and SHA-256 (an LFS file's etag); returns its SHA-256."""
    got = path.stat().st_size
    if size is not None and got != size:
        _forget(path)
        raise HubError(
            f"{url}: downloaded {got} bytes, the hub reports {size}; the partial file was removed, "
            "run the command again"
        )
    from .state_dict_file import sha256_of

    digest = sha256_of(path)
    if etag and _SHA256.match(etag) and digest != etag:
        _forget(path)
        raise HubError(
            f"{url}: SHA-256 {digest} of the download differs from the hub's {etag}; the file was "
            "removed from the cache, run the command again"
        )
    return digest


def download(source: str, progress: bool = True) -> tuple[Path, dict]:
    """The local path of the hub file (cached; resumed when a previous run was interrupted) and what the
    hub reported: {"hub": "hf:ORG/NAME@REV/PATH", "url", "commit", "bytes", "sha256"}."""
    hub = _hub()
    src = parse_source(source)
    url = src.url()
    if not progress:
        hub.utils.disable_progress_bars()
    try:
        meta = hub.get_hf_file_metadata(url)
        path = Path(hub.hf_hub_download(src.repo_id, src.filename, revision=src.revision))
    except HubError:
        raise
    except Exception as e:  # noqa: BLE001 - huggingface_hub raises many kinds; each becomes one message
        raise HubError(f"{url}: {_reason(e, src)}") from e
    digest = _check(path, src, url, meta.size, meta.etag)
    return path, {
        "hub": f"hf:{src.repo_id}@{meta.commit_hash or src.revision}/{src.filename}",
        "url": url,
        "commit": meta.commit_hash,
        "bytes": path.stat().st_size,
        "sha256": digest,
    }
