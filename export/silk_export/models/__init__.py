"""The networks: the Architecture interface every registered network family implements
(architecture.py) and the registry of them (registry.py), model sizes, Silk's own
architecture (silk_model.py, point_encoder.py, layers.py) and training checkpoints."""
