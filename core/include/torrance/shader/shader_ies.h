// The IES Texture node (opcode 63 of the texture family) as Cycles 3.4 renders it (svm/ies.h):
//   TexIES (63)  in0 Vector (a direction, not normalised; 0 gives 0), in1.x Strength; a table:
//     h_num, v_num, then h_num horizontal angles (radians, 0 .. 2 pi, the last 2 pi), v_num
//     vertical angles (radians, from 0 = straight down, -Z), then the intensities, h_num rows of
//     v_num (Cycles' IESFile::pack, the counts as floats)
//   mode: IesLookup, the Cycles whose kernel_ies_interp the op follows
// The add-on parses the LM-63 text and pads the table as Cycles' util/ies.cpp does
// (python_addon/torrance/shader_graph/ies.py). The op writes Fac = Strength x the intensity
// at the direction's angles, Cycles' Catmull-Rom interpolation over vertical then horizontal
// angles, 0 past the last vertical angle; an inconsistent table gives 0.
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

// Cycles 3.4 clamps the last vertical neighbour and always wraps the horizontal ones; Cycles
// 4.x gives 0 outside the table's angles and takes neighbours past either end as 0 unless the
// table reaches the pole or the full circle, tested in float as Cycles does (a table ending at
// exactly 2 pi or pi, as Cycles' own padding does, does not count as reaching it).
enum class IesLookup : uint8_t { Cycles3, Cycles4 };
constexpr int kIesLookups = int(IesLookup::Cycles4) + 1;

// The table's intensity at horizontal angle h (0 .. 2 pi) and vertical angle v (0 .. pi).
float ies_intensity(const float* table, int size, float h, float v, IesLookup lookup = IesLookup::Cycles3);

OpValue ies_op(const ShaderOpContext& c);

}  // namespace torrance::shader
