# SPDX-License-Identifier: MIT
"""The released Mesh Silksong network (arch "official", docs/official_network.md): its
re-implementation, the release checkpoint's key layout and loader, and its model card.
`silk-export import-official`, which turns a released checkpoint into a Silk model folder, is
silk_export/import_official.py (it exports through onnx/, a later stage)."""
