"""Torrance's C++ shading core (Embree + Cook-Torrance path tracer), for Python and Blender."""
from ._core import (PASSES, Denoiser, RecordedRays, RenderResult, RenderSession, RenderSettings,
                    Scene, __version__, corner_normals, cryptomatte_hash, directional_albedo,
                    hosek_sky_table, nishita_sky_table, preetham_sky_table, read_image,
                    record_rays, render, replay_rays, scattering_sky_table, transform_points,
                    triangle_normals, vertex_normals, write_image)

__all__ = ["PASSES", "Denoiser", "RecordedRays", "RenderResult", "RenderSession", "RenderSettings",
           "Scene",
           "corner_normals", "cryptomatte_hash", "directional_albedo", "hosek_sky_table",
           "nishita_sky_table", "preetham_sky_table", "read_image", "record_rays", "render",
           "replay_rays", "scattering_sky_table", "transform_points", "triangle_normals",
           "vertex_normals", "write_image", "__version__"]
