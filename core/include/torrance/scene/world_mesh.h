// A mesh's arrays in world space, in bulk, for the add-on's export (export/mesh.py world_mesh):
// positions, geometric normals and corner normals, each what the export's numpy code computed,
// in the same precision and bit for bit the same, but in one parallel pass instead of numpy's
// temporaries and gathers (issue 11: ~2 s of a 10 M-triangle export; issue 10: 3-5 ms of a
// 50k-triangle F12). Every operation rounds on its own (no fused multiply-add), in numpy's order,
// and denormals are kept whatever the calling thread's mode.
#pragma once

#include <cstddef>
#include <cstdint>

namespace torrance {

// positions: num_vertices xyz; triangles: num_triangles vertex-index triples, each in
// [0, num_vertices) (std::invalid_argument naming the first one outside otherwise).
// Writes normals (num_triangles xyz): the unit normal of the counter-clockwise winding, or 0 where
// it cannot be normalised; usable (num_triangles): 1 where its length is finite and > 1e-30.
// Every operation is float32, in numpy's order: p1 - p0, p2 - p0; x = a.y * b.z - a.z * b.y (and
// cyclic); len = sqrt((x * x + y * y) + z * z); n = v / len.
void triangle_normals(const float* positions, size_t num_vertices, const int32_t* triangles, size_t num_triangles,
                      float* normals, uint8_t* usable);

// Points (count xyz, float32) moved by the affine 4x4 row-major matrix (float64), in float64 and
// then rounded to float32 (beyond float32's range: +-Inf): out[r] = ((p.x m[r][0] + p.y m[r][1]) +
// p.z m[r][2]) + m[r][3].
void transform_points(const float* points, size_t count, const double* matrix, float* out);

// Corner normals (num_triangles x 3 corners xyz) of a mesh whose normals are given per vertex
// (per_vertex: num_normals == num_vertices entries, read through triangles, whose indices are
// checked as by triangle_normals) or per corner (num_normals == 3 num_triangles, in order):
// each normal times matrix^T (3x3 row-major float32; null: as it is), ((v.x m[r][0] + v.y m[r][1])
// + v.z m[r][2]), then normalised as in triangle_normals. A corner whose normal cannot be
// normalised, and every corner of a flat triangle (smooth[i] == 0; smooth null: none is flat),
// takes its triangle's geometric normal (geometric: num_triangles xyz).
void corner_normals(const float* normals, size_t num_normals, bool per_vertex, const int32_t* triangles,
                    size_t num_triangles, const float* matrix, const uint8_t* smooth, const float* geometric,
                    float* out);

}  // namespace torrance
