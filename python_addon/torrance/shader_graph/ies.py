# SPDX-License-Identifier: Apache-2.0
"""The IES Texture node as Cycles renders it (opcode 63, the core's shader_ies.h): a light's
photometric distribution from an IES LM-63 text (a Text data-block or a file), Fac = Strength x
the candela table at the Vector's direction.

The reader parses the text and pads its table as Cycles 3.4's host does (util/ies.cpp: the
parser's quirks, photometric types B and C, the symmetric quarters and halves mirrored to the
whole circle, the 360 degree row, candela x multiplier x ballast factors x 4 pi / 177.83 to
Cycles' watts); the twin evaluates the table as the core's op does (float32, Cycles' Catmull-Rom
interpolation over vertical then horizontal angles): the fold of a constant Vector and the
reference evaluator's op. Text Cycles can not read (no data-block, an unreadable file, type A,
angle ranges it rejects) Cycles renders as 100 x Strength; the reader reports it instead.

Cycles 4.x (node_versions.cycles4_ies; measured in 4.2) parses without 3.4's end-of-text
failure, keeps a type C table of vertical angles 90-180 as it is, looks up with its own wraps
(the op's mode 1) and processes type B photometry anew; that last is reported there.
"""

import math
import re

import numpy as np

OPCODES = {"TexIES": 63}

_F = np.float32
_PI = _F(math.pi)
_DEG = _F(_PI / _F(180.0))
# Candela to Cycles' W/sr x 4 pi: the D65 illuminant's luminous efficacy, 177.83 lm/W.
CANDELA_TO_WATT = 0.0706650768394
TYPE_B, TYPE_C = 2, 1
_SPACE = " \t\n\v\f\r"
_DOUBLE = re.compile(r"[ \t\n\v\f\r]*([+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
                     r"|inf(?:inity)?|nan))", re.IGNORECASE)
_LONG = re.compile(r"[ \t\n\v\f\r]*([+-]?\d+)")


class IESError(ValueError):
    """Text Cycles does not read as an IES file (the message says why)."""


class _Numbers:
    """The numbers of the text as Cycles' parser reads them (strtod / strtol from a cursor; a
    failed read ends the text)."""

    def __init__(self, text, pos):
        self.text, self.pos = text, pos
        self.error = False                  # a read past the end or of no number

    def eof(self):
        return self.pos is None or self.pos >= len(self.text) or self.text[self.pos] == "\0"

    def _read(self, pattern, cast):
        if self.eof():
            self.error = True
            return cast(0)
        m = pattern.match(self.text, self.pos)
        if m is None:
            self.pos, self.error = None, True
            return cast(0)
        self.pos = m.end()
        return cast(m.group(1))

    def double(self):
        return self._read(_DOUBLE, float)

    def long(self):
        return self._read(_LONG, int)


def parse(text, cycles4=False):
    """(type, v_angles, h_angles, intensity rows per horizontal angle) of an LM-63 text, the
    values as Cycles' IESFile::parse stores them (float32, intensities in its watts)."""
    text = text.replace(",", " ")
    start = text.find("\nTILT=")
    if start < 0:
        raise IESError("no TILT= line")
    n = _Numbers(text, start)
    if text.startswith("\nTILT=INCLUDE", start):
        n.pos += 13
        n.double()                          # lamp to luminaire geometry
        for _ in range(2 * max(n.long(), 0)):
            n.double()                      # tilt angles and factors
    else:
        nl = text.find("\n", start + 1)
        n.pos = nl if nl >= 0 else None
    if n.eof():
        raise IESError("the text ends after its TILT line")
    n.pos += 1
    n.long()                                # lamps
    n.double()                              # lumens per lamp
    factor = n.double()                     # candela multiplier
    v_num, h_num, kind = n.long(), n.long(), n.long()
    if kind not in (TYPE_B, TYPE_C):
        raise IESError(f"photometric type {'A' if kind == 3 else kind}; Cycles reads types B and C")
    n.long()                                # units
    n.double(), n.double(), n.double()      # width, length, height
    factor *= n.double()                    # ballast factor
    factor *= n.double()                    # ballast-lamp photometric factor
    n.double()                              # input watts
    factor *= CANDELA_TO_WATT
    if v_num * max(h_num, 1) > len(text) or h_num > len(text):
        raise IESError(f"{v_num} x {h_num} angles in a text of {len(text)} characters")
    v = [_F(n.double()) for _ in range(max(v_num, 0))]
    h = [_F(n.double()) for _ in range(max(h_num, 0))]
    rows = [[_F(factor * n.double()) for _ in range(max(v_num, 0))] for _ in range(max(h_num, 0))]
    if n.error if cycles4 else n.eof():
        # Cycles 3.4's parser fails when its cursor ends the text (a number missing, or the
        # last one the text's last characters); 4.x's when a number is missing.
        raise IESError("the candela values are missing" if cycles4
                       else "the candela values end the text or are missing")
    return kind, v, h, rows


def _mirror(angles, rows, about):
    """Appends angles about - a (a from the second last down) and their rows."""
    for i in range(len(angles) - 2, -1, -1):
        angles.append(_F(about) - angles[i])
        rows.append(rows[i])


def _process_c(v, h, rows, cycles4):
    if h[0] == _F(90):
        h[:] = [a - _F(90) for a in h]
    if h[0] != 0:
        raise IESError(f"horizontal angles from {float(h[0]):g} degrees")
    if len(h) == 1:
        h.append(_F(360))
        rows.append(rows[0])
    if h[-1] == _F(90):
        _mirror(h, rows, 180)
    if h[-1] == _F(180):
        _mirror(h, rows, 360)
    if h[-1] != _F(360):
        difference = _F(360) - h[-1]
        if h[-1] - h[-2] == difference or h[1] - h[0] == difference:
            h.append(_F(360))
            rows.append(rows[0])
        else:
            raise IESError(f"horizontal angles up to {float(h[-1]):g} degrees")
    if v[0] == _F(90):
        if v[-1] != _F(180):
            raise IESError(f"vertical angles 90 to {float(v[-1]):g} degrees")
        # Cycles 3.4 turns 90..180 into 90..0 (descending: its kernel then gives 0 everywhere).
        if not cycles4:
            v[:] = [_F(180) - a for a in v]
    elif v[0] != 0:
        raise IESError(f"vertical angles from {float(v[0]):g} degrees")


def _process_b(v, h, rows):
    rows[:] = [list(col) for col in zip(*rows, strict=True)] if rows else []
    v, h = h, v
    if h[-1] != _F(90):
        raise IESError("type B horizontal angles not ending at 90 degrees")
    if h[0] == 0:
        h[:] = [_F(90) - a for a in h[:0:-1]] + [_F(90) + a for a in h]
        rows[:] = rows[:0:-1] + rows
    elif h[0] == _F(-90):
        h[:] = [a + _F(90) for a in h]
    h.append(_F(360))
    rows.append(rows[0])
    if v[-1] != _F(90):
        raise IESError("type B vertical angles not ending at 90 degrees")
    if v[0] == 0:
        v[:] = [_F(90) - a for a in v[:0:-1]] + [_F(90) + a for a in v]
        # Cycles mirrors the rows one value short of the angles (its loop starts a row lower).
        rows[:] = [row[-2::-1] + row for row in rows]
    elif v[0] == _F(-90):
        v[:] = [a + _F(90) for a in v]
    return v, h


def ies_table(text, cycles4=False):
    """The op's table (Cycles' packed IES: counts, horizontal and vertical angles in radians,
    the rows) of an LM-63 text; raises IESError where Cycles' IESFile::load fails (cycles4:
    as Cycles 4.x's; its type B processing is not reproduced)."""
    kind, v, h, rows = parse(text, cycles4)
    if not v or not h:
        raise IESError("no angles")
    if kind == TYPE_B and cycles4:
        raise IESError("type B photometry, which Cycles 4.x processes in a way Torrance does "
                       "not reproduce")
    if kind == TYPE_B:
        v, h = _process_b(v, h, rows)
    else:
        _process_c(v, h, rows, cycles4)
    h = [a * _DEG for a in h]
    v = [a * _DEG for a in v]
    return [float(len(h)), float(len(v)), *map(float, h), *map(float, v),
            *(float(x) for row in rows for x in row)]


# -- the twin -----------------------------------------------------------------------------------

def _catmull_rom(a, b, c, d, x):
    return (_F(0.5) * (((d + _F(3) * (b - c) - a) * x + (_F(2) * a - _F(5) * b + _F(4) * c - d))
                       * x + (c - a)) * x + b)


def _fraction(a, b, x):
    return (x - a) / (b - a) if b != a else _F(0)


# Cycles 4.x's wrap tests, in float32 (pi - 1e-7 and 2 pi - 1e-7 round back to pi, 2 pi).
_EPS = _F(1e-7)
_NEAR_PI = _F(_PI - _EPS)
_NEAR_TWO_PI = _F(_F(2) * _PI - _EPS)


def intensity(table, h, v, cycles4=False):
    """The table's intensity at horizontal angle h and vertical angle v (radians), as the
    core's ies_intensity (cycles4: Cycles 4.x's lookup, the op's mode 1)."""
    t = np.asarray(table, np.float32)
    if len(t) < 2 or not (t[0] >= 2 and t[1] >= 1 and t[0] < 1e6 and t[1] < 1e6):
        return _F(0)
    h_num, v_num = int(t[0]), int(t[1])
    if len(t) != 2 + h_num + v_num + h_num * v_num:
        return _F(0)
    hs, vs = t[2:2 + h_num], t[2 + h_num:2 + h_num + v_num]
    rows = t[2 + h_num + v_num:].reshape(h_num, v_num)
    h, v = _F(h), _F(v)
    if v_num < 2 or not v < vs[-1]:
        return _F(0)
    low, high, clamp_high, around = True, False, True, True
    if cycles4:
        if v < vs[0] or h < hs[0] or h >= hs[-1]:
            return _F(0)
        low, high, clamp_high = vs[0] < _EPS, vs[-1] > _NEAR_PI, False
        around = hs[0] < _EPS and hs[-1] > _NEAR_TWO_PI
    h_i = v_i = 0
    while h_i + 2 < h_num and hs[h_i + 1] < h:
        h_i += 1
    while v_i + 2 < v_num and vs[v_i + 1] < v:
        v_i += 1
    h_frac, v_frac = _fraction(hs[h_i], hs[h_i + 1], h), _fraction(vs[v_i], vs[v_i + 1], v)

    def vertical(k):
        r = rows[k]
        before = r[v_i - 1] if v_i > 0 else (r[1] if low else _F(0))
        if clamp_high:
            after = r[min(v_i + 2, v_num - 1)]
        else:
            after = r[v_i + 2] if v_i + 2 < v_num else (r[v_num - 2] if high else _F(0))
        return _catmull_rom(before, r[v_i], r[v_i + 1], after, v_frac)

    a = vertical(h_i - 1) if h_i > 0 else (vertical(h_num - 2) if around else _F(0))
    b, c = vertical(h_i), vertical(h_i + 1)
    d = vertical(h_i + 2) if h_i + 2 < h_num else (vertical(1) if around else _F(0))
    return max(_catmull_rom(a, b, c, d, h_frac), _F(0))


def angles(vector):
    """(horizontal, vertical) angles of a direction as Cycles' svm_node_ies: v from -Z, h =
    atan2(x, y) + pi; None for a zero or non-finite vector."""
    d = np.asarray(vector[:3], np.float32)
    length = _F(math.sqrt(float(d @ d)))
    if not (length > 0 and math.isfinite(length)):
        return None
    d = d / length
    v = _F(math.acos(min(max(-float(d[2]), -1.0), 1.0)))
    return _F(_F(math.atan2(float(d[0]), float(d[1]))) + _PI), v


def _fold_ies(mode, flags, a, table):
    hv = angles(a[0])
    fac = 0.0 if hv is None else float(_F(a[1][0]) * intensity(table, *hv, cycles4=mode == 1))
    return (fac, 0.0, 0.0, 0.0)


FOLDS = {"TexIES": _fold_ies}


# -- the reader ---------------------------------------------------------------------------------

def ies_text(node):
    """The IES text Cycles reads for a node: its Text data-block's lines, each ended by a
    newline (Internal), or the file's bytes (External, '//' from the blend file); None if
    there is none (Cycles then reads an empty line)."""
    if node.mode == 'INTERNAL':
        if node.ies is None:
            return None
        return "".join(line.body + "\n" for line in node.ies.lines)
    import bpy
    path = bpy.path.abspath(node.filepath, library=node.id_data.library)
    if not node.filepath:
        return None
    try:
        with open(path, "rb") as f:
            return f.read().decode("latin-1")
    except OSError:
        return None


def _default_vector(g):
    """The Vector Cycles links to an unlinked input: 3.x's Texture Coordinate > Normal (the
    normal in the owner's object space; at a point or spot light, the direction from the light
    to the receiver), 4.x's Geometry > Incoming moved to object space as a normal."""
    from .geometry import object_space_normal, to_object_space
    from .node_versions import cycles4_ies
    if cycles4_ies():
        return to_object_space(g, g.builder.emit("Geometry", 'vector', mode=3))
    return object_space_normal(g)


def _read_ies(g, node, socket):
    from ..nodes import node_label
    from .graph import Unsupported
    from .node_versions import cycles4_ies
    cycles4 = cycles4_ies()
    text = ies_text(node)
    where = "its Text" if node.mode == 'INTERNAL' else f"the file '{node.filepath}'"
    try:
        if text is None:
            raise IESError("none given" if node.mode == 'INTERNAL' or not node.filepath
                           else "it can not be read")
        table = ies_table(text, cycles4)
    except IESError as exc:
        raise Unsupported(f"{node_label(node)}: {where} is not IES data Cycles reads ({exc}); "
                          f"Cycles renders it as 100 x Strength") from None
    vector = node.inputs["Vector"]
    v = g.input(vector, 'vector') if vector.is_linked else _default_vector(g)
    return g.builder.emit("TexIES", 'float', [v, g.input(node.inputs["Strength"], 'float')],
                          mode=int(cycles4), table=table)


READERS = {'ShaderNodeTexIES': _read_ies}
