"""The networks: the registry of architectures (registry.py), model sizes, Silk's own
architecture (silk_model.py, point_encoder.py, layers.py) and training checkpoints."""
