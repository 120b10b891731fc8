// Smooth-shading vertex normals of a polygon mesh, computed the same way every time.
//
// Why: Blender (3.4 at least) sums each vertex's normal from its polygons on several threads with
// atomic float additions, so the order of the sum, and the normal's last bits, change from one
// read of the mesh to the next. Those bits move a few camera paths (a ray grazing a sphere's
// silhouette bounces another way), and the same F12 then gives another image. The export reads
// the polygons and sums their normals here, in a fixed order.
#pragma once

#include <cstddef>
#include <cstdint>

namespace torrance {

// Blender's definition and arithmetic: a vertex's normal is the sum, over the polygon corners at
// it, of the polygon's unit normal (Newell's; (0, 0, 1) for a polygon without one) times the
// corner's angle (between its two edges, each normalised; an edge of length 0 makes a right
// angle), normalised; where that sum can not be normalised, the vertex's position normalised, or
// 0. Every operation in float as Blender's (reciprocal-length normalisation, no fused
// multiply-add), and the sums taken polygon by polygon: the normals Blender computes when its
// threads happen to take the polygons in order, as they do for every vertex whose polygons fall
// in one of its blocks of 1024.
// positions: num_vertices xyz; corner_vertices: the vertex of each corner (num_corners);
// polygon_starts and polygon_sizes: each polygon's first corner and its number of corners
// (polygons of fewer than 3 corners add nothing). Writes num_vertices xyz to out.
// Indices out of range: std::invalid_argument naming the first one.
void vertex_normals(const float* positions, size_t num_vertices, const int32_t* corner_vertices, size_t num_corners,
                    const int32_t* polygon_starts, const int32_t* polygon_sizes, size_t num_polygons, float* out);

}  // namespace torrance
