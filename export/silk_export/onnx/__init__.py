# SPDX-License-Identifier: MIT
"""ONNX: the encoder and decoder graphs of docs/model_contract.md over any registered
architecture, the exporter that writes a model folder (graphs, INT8 / INT4 decoders, model.json),
and an onnxruntime loop in Python used to measure a quantized decoder's fidelity."""
