# SPDX-License-Identifier: MIT
"""How good a model is: held-out loss on a split (`silk-export loss`), generating meshes from a
checkpoint or a model folder with libsilk's runtime (`silk-export generate`), and geometric
metrics and structure of generated meshes against their inputs (`silk-export eval`)."""
