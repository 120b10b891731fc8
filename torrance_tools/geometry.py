# SPDX-License-Identifier: Apache-2.0
"""Triangle meshes as numpy arrays (no bpy): grids and spheres, for the scene builders
(torrance_tools.scene) and for scenes handed straight to torrance_core (scripts/analysis.py)."""

import numpy as np


def grid(xs, ys):
    """Vertices (nx*ny, 3) at z = 0 over the coordinate arrays xs (nx,), ys (ny,), and the
    triangles of the (nx-1)*(ny-1) cells, two per cell."""
    nx, ny = len(xs), len(ys)
    X, Y = np.meshgrid(xs, ys)                       # (ny, nx)
    verts = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1))
    a = (j * nx + i).ravel()
    b, c, d = a + 1, a + nx + 1, a + nx
    tris = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return verts, tris


def blade(height=0.2, width=0.01, bend=0.04, segments=5, taper=0.8):
    """A grass blade along +Z from the origin: a strip of `segments` quads (2 * segments
    triangles) narrowing by `taper` to the tip and bent towards +Y (tip offset `bend`).
    Returns verts (2 * (segments + 1), 3) and quads (segments, 4)."""
    t = np.linspace(0.0, 1.0, segments + 1)
    w = 0.5 * width * (1.0 - taper * t)
    y, z = bend * t * t, height * t
    verts = np.stack([np.stack([-w, y, z], 1), np.stack([w, y, z], 1)], 1).reshape(-1, 3)
    i = 2 * np.arange(segments)
    quads = np.stack([i, i + 1, i + 3, i + 2], 1)
    return verts, quads


def icosphere(subdivisions):
    """Unit icosphere: vertices (N,3) on the sphere and triangles (M,3), outward winding."""
    t = (1.0 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [np.array(p, dtype=np.float64) / np.linalg.norm(p) for p in v]
    faces = f
    for _ in range(subdivisions):
        cache = {}

        def mid(a, b, cache=cache):
            key = (a, b) if a < b else (b, a)
            if key not in cache:
                p = verts[a] + verts[b]
                verts.append(p / np.linalg.norm(p))
                cache[key] = len(verts) - 1
            return cache[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return np.array(verts), np.array(faces, dtype=np.int64)


def uv_sphere(segments=32, rings=16):
    """Unit UV sphere: vertices (N,3), triangles (M,3), outward winding."""
    theta = np.pi * np.arange(1, rings) / rings              # polar angle of the inner rings
    phi = 2 * np.pi * np.arange(segments) / segments
    T, P = np.meshgrid(theta, phi, indexing="ij")            # (rings-1, segments)
    ring = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], -1).reshape(-1, 3)
    verts = np.concatenate([[[0, 0, 1]], ring, [[0, 0, -1]]])
    top, bottom = 0, len(verts) - 1
    s = np.arange(segments)
    s1 = (s + 1) % segments
    tris = [np.stack([np.full(segments, top), 1 + s, 1 + s1], 1)]
    for r in range(rings - 2):
        a, b = 1 + r * segments + s, 1 + r * segments + s1
        c, d = a + segments, b + segments
        tris += [np.stack([a, c, d], 1), np.stack([a, d, b], 1)]
    last = 1 + (rings - 2) * segments
    tris.append(np.stack([last + s, np.full(segments, bottom), last + s1], 1))
    return verts, np.concatenate(tris)


def uv_sphere_with_normals(center, radius, segments=48, rings=24):
    """A UV sphere (uv_sphere) of `radius` at `center` as torrance_core.Scene.add_mesh takes it:
    float32 positions (N, 3), int32 triangles (M, 3) and the exact normals at each triangle
    corner, float32 (M, 3, 3)."""
    verts, tris = uv_sphere(segments, rings)
    positions = (verts * radius + np.asarray(center)).astype(np.float32)
    return positions, tris.astype(np.int32), verts[tris].astype(np.float32)
