#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A model hub on 127.0.0.1 for tests: serves folders in the hub's URL layout
(/ORG/NAME/resolve/REVISION/PATH) with the headers huggingface_hub reads (X-Repo-Commit, ETag,
X-Linked-Etag = the file's SHA-256, X-Linked-Size, Content-Length, byte ranges for resumed downloads,
X-Error-Code on a 404), so `silk-export import-official hf:...` is tested without any network.
Faults on demand: the first N GETs cut off half-way (a truncated download), a wrong SHA-256.

    local_hub.py --repo gcsong/mesh_silksong=DIR [--port P] [--truncate N] [--wrong-hash]
      prints the endpoint (for HF_ENDPOINT) and serves until interrupted. DIR's files appear under
      the revision "main" (and the commit hash the server prints)."""

from __future__ import annotations

import argparse
import hashlib
import re
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

COMMIT = "0123456789abcdef0123456789abcdef01234567"
_RESOLVE = re.compile(r"^/(?P<repo>[^/]+/[^/]+)/resolve/(?P<rev>[^/]+)/(?P<path>[^?]+)")


class LocalHub:
    """with LocalHub({"org/name": folder}) as hub: hub.endpoint, hub.requests (method, path, Range)."""

    def __init__(self, repos: dict, truncate_gets: int = 0, wrong_hash: bool = False, port: int = 0):
        self.repos = {k: Path(v) for k, v in repos.items()}
        self.truncate_gets, self.wrong_hash = truncate_gets, wrong_hash
        self.requests: list[tuple[str, str, str | None]] = []
        self._sha: dict[Path, str] = {}
        self._server = ThreadingHTTPServer(("127.0.0.1", port), self._handler())
        self._server.daemon_threads = True
        self.endpoint = f"http://127.0.0.1:{self._server.server_address[1]}"

    def sha256(self, path: Path) -> str:
        if path not in self._sha:
            self._sha[path] = hashlib.sha256(path.read_bytes()).hexdigest()
        return self._sha[path]

    def __enter__(self):
        threading.Thread(target=self._server.serve_forever, daemon=True).start()
        return self

    def __exit__(self, *exc):
        self._server.shutdown()
        self._server.server_close()

    def _handler(self):
        hub = self

        class Handler(BaseHTTPRequestHandler):
            protocol_version = "HTTP/1.1"

            def log_message(self, *args):  # quiet
                pass

            def _error(self, code: int, error_code: str, message: str, commit: bool = False):
                body = message.encode()
                self.send_response(code)
                self.send_header("X-Error-Code", error_code)
                self.send_header("X-Error-Message", message)
                if commit:
                    self.send_header("X-Repo-Commit", COMMIT)
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                if self.command != "HEAD":
                    self.wfile.write(body)

            def _serve(self):
                hub.requests.append((self.command, self.path, self.headers.get("Range")))
                m = _RESOLVE.match(self.path)
                folder = hub.repos.get(m["repo"]) if m else None
                if folder is None:
                    return self._error(401, "RepoNotFound", "Repository not found")
                if m["rev"] not in ("main", COMMIT):
                    return self._error(404, "RevisionNotFound", f"Invalid rev id: {m['rev']}")
                f = (folder / m["path"]).resolve()
                if not f.is_file() or folder.resolve() not in f.parents:
                    return self._error(404, "EntryNotFound", "Entry not found", commit=True)
                self._send_file(f)

            def _send_file(self, f: Path):
                size = f.stat().st_size
                sha = "0" * 64 if hub.wrong_hash else hub.sha256(f)
                start = 0
                rng = re.match(r"bytes=(\d+)-$", self.headers.get("Range") or "")
                if rng and self.command == "GET":
                    start = min(int(rng[1]), size)
                self.send_response(206 if start else 200)
                self.send_header("X-Repo-Commit", COMMIT)
                self.send_header("ETag", f'"{sha}"')
                self.send_header("X-Linked-Etag", f'"{sha}"')
                self.send_header("X-Linked-Size", str(size))
                self.send_header("Accept-Ranges", "bytes")
                self.send_header("Content-Length", str(size - start))
                if start:
                    self.send_header("Content-Range", f"bytes {start}-{size - 1}/{size}")
                self.end_headers()
                if self.command == "HEAD":
                    return
                data = f.read_bytes()[start:]
                if hub.truncate_gets > 0:
                    hub.truncate_gets -= 1
                    self.wfile.write(data[: len(data) // 2])
                    self.wfile.flush()
                    self.close_connection = True
                    return
                self.wfile.write(data)

            do_GET = do_HEAD = _serve

        return Handler


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repo", action="append", required=True, help="ORG/NAME=FOLDER")
    ap.add_argument("--port", type=int, default=0)
    ap.add_argument("--truncate", type=int, default=0, help="cut off the first N GETs half-way")
    ap.add_argument("--wrong-hash", action="store_true", help="report a wrong SHA-256")
    a = ap.parse_args()
    repos = dict(r.split("=", 1) for r in a.repo)
    with LocalHub(repos, a.truncate, a.wrong_hash, a.port) as hub:
        print(hub.endpoint, "commit", COMMIT, flush=True)
        threading.Event().wait()


if __name__ == "__main__":
    main()
