# SPDX-License-Identifier: MIT
"""Training data, built through libsilk: finding mesh files, the train/val/test/dev split, the
sharded token cache (`silk-export dataset`) and the online per-sample pipeline (augmentation,
tokenization, point cloud, resampling) that turns a mesh into a model input."""
