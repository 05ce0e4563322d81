# SPDX-License-Identifier: MIT
"""The networks: the Architecture interface every registered network family implements
(architecture.py; the registry of them is silk_export/registry.py), model sizes, Silk's own
architecture (silk_model.py, point_encoder.py, layers.py); checkpoints are silk_export/checkpoint.py."""
