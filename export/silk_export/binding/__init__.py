"""The ctypes binding to libsilk's C API (engine/include/silk/silk.h): silk_c.py declares the C
functions, structs and status codes (pure ctypes, shared with the Blender add-on), libsilk.py
loads the library and wraps meshes, tokens, point pre-processing and generation for Python.

Self-contained: it needs only numpy and where the checkout keeps a built library (paths.py)."""
