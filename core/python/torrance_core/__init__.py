"""Torrance's C++ shading core (Embree + Cook-Torrance path tracer), for Python and Blender."""
from ._core import (PASSES, RenderResult, RenderSettings, Scene, __version__, directional_albedo, read_image,
                    render, write_image)

__all__ = ["PASSES", "RenderResult", "RenderSettings", "Scene", "directional_albedo", "read_image", "render",
           "write_image", "__version__"]
