"""Torrance's C++ shading core (Embree + Cook-Torrance path tracer), for Python and Blender."""
from ._core import (PASSES, RenderResult, RenderSession, RenderSettings, Scene, __version__,
                    directional_albedo, read_image, render, triangle_normals, write_image)

__all__ = ["PASSES", "RenderResult", "RenderSession", "RenderSettings", "Scene",
           "directional_albedo", "read_image", "render", "triangle_normals", "write_image",
           "__version__"]
