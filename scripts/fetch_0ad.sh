#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fetches the 0 A.D. art meshes (PMD) used by the benchmark and the PMD cross-check test:
# Debian's 0ad-data package -> public.zip -> art/meshes/**.pmd. Idempotent; data stays out of the repo.
#
#   scripts/fetch_0ad.sh            # cache in /tmp/silk-data (override with SILK_DATA_DIR)
#   SILK_0AD_MESHES=$SILK_DATA_DIR/0ad/art/meshes  (what the tests and the bench then read)
#
# The .deb is about 1.4 GB and unpacks to about the same again; the extracted meshes are ~150 MB.
# License of the data: CC BY-SA 3.0, (c) Wildfire Games and the 0 A.D. contributors.
set -euo pipefail

DATA_DIR=${SILK_DATA_DIR:-/tmp/silk-data}
OUT_DIR="$DATA_DIR/0ad"
UNPACK_DIR="$DATA_DIR/0ad-data-unpacked"
mkdir -p "$DATA_DIR" "$OUT_DIR"

# 1. The package (skipped when a copy is already in the cache).
deb=$(ls "$DATA_DIR"/0ad-data_*_all.deb 2>/dev/null | head -n 1 || true)
if [ -z "$deb" ]; then
  echo "fetch_0ad: downloading 0ad-data (~1.4 GB) into $DATA_DIR"
  (cd "$DATA_DIR" && apt-get download 0ad-data)
  deb=$(ls "$DATA_DIR"/0ad-data_*_all.deb | head -n 1)
else
  echo "fetch_0ad: using cached $(basename "$deb")"
fi

# 2. Unpack it (skipped when public.zip is already there).
zip=$(find "$UNPACK_DIR" -name public.zip -path '*mods/public/*' 2>/dev/null | head -n 1 || true)
if [ -z "$zip" ]; then
  echo "fetch_0ad: unpacking $(basename "$deb")"
  rm -rf "$UNPACK_DIR.partial"
  dpkg-deb -x "$deb" "$UNPACK_DIR.partial"
  rm -rf "$UNPACK_DIR"
  mv "$UNPACK_DIR.partial" "$UNPACK_DIR"
  zip=$(find "$UNPACK_DIR" -name public.zip -path '*mods/public/*' | head -n 1)
fi
[ -n "$zip" ] || { echo "fetch_0ad: no public.zip in the package" >&2; exit 1; }

# 3. Extract art/meshes/**.pmd (files already present with the right size are kept).
python3 - "$zip" "$OUT_DIR" <<'EOF'
import collections, os, sys, zipfile
zip_path, out_dir = sys.argv[1], sys.argv[2]
root = os.path.realpath(out_dir)
written = 0
per_top = collections.Counter()
with zipfile.ZipFile(zip_path) as z:
    for info in z.infolist():
        name = info.filename
        if info.is_dir() or not name.startswith("art/meshes/") or not name.lower().endswith(".pmd"):
            continue
        dest = os.path.realpath(os.path.join(out_dir, name))
        if not dest.startswith(root + os.sep):
            sys.exit("fetch_0ad: refusing unsafe path in zip: " + name)
        rel = name[len("art/meshes/"):]
        per_top[rel.split("/")[0] if "/" in rel else "(top)"] += 1
        if os.path.isfile(dest) and os.path.getsize(dest) == info.file_size:
            continue
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        tmp = dest + ".tmp"
        with z.open(info) as src, open(tmp, "wb") as dst:
            dst.write(src.read())
        os.replace(tmp, dest)
        written += 1
total = sum(per_top.values())
print(f"fetch_0ad: {total} PMD files under {os.path.join(out_dir, 'art/meshes')} ({written} newly written)")
for top, n in sorted(per_top.items()):
    print(f"  {top:<12} {n}")
EOF
echo "fetch_0ad: export SILK_0AD_MESHES=$OUT_DIR/art/meshes"
