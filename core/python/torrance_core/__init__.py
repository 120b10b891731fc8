"""Torrance's C++ shading core (Embree + Cook-Torrance path tracer), for Python and Blender."""
from ._core import (PASSES, RecordedRays, RenderResult, RenderSession, RenderSettings, Scene,
                    __version__, directional_albedo, read_image, record_rays, render, replay_rays,
                    triangle_normals, write_image)

__all__ = ["PASSES", "RecordedRays", "RenderResult", "RenderSession", "RenderSettings", "Scene",
           "directional_albedo", "read_image", "record_rays", "render", "replay_rays",
           "triangle_normals", "write_image", "__version__"]
