# SPDX-License-Identifier: Apache-2.0
"""IES LM-63 texts the IES Texture's tests share (core/python/tests/test_shader_ies_ops.py,
blender_tests/test_shader_ies_agreement.py): realistic photometric types and the quirks Cycles'
parser meets. No bpy."""

# Type C, 7 horizontal angles over the whole circle (unevenly spaced, the 360 row repeating the
# 0 one), 12 vertical ones from straight down to straight up: an asymmetric distribution.
TYPE_C_FULL = """IESNA:LM-63-2002
[TEST] Torrance asymmetric type C
TILT=NONE
1 1000 1.0 12 7 1 2 0.3 0.3 0.1
1.0 1.0 60
0 10 20 35 50 65 80 90 105 120 150 180
0 45 90 180 270 315 360
1000 980 900 640 300 120 60 30 20 15 10 5
1000 900 700 420 380 520 260 90 40 20 10 5
1000 860 520 200 90 60 30 10 5 0 0 0
1000 990 950 880 700 420 200 80 50 30 20 5
1000 800 400 150 60 260 700 300 100 40 10 5
1000 940 820 600 420 300 160 70 30 15 10 5
1000 980 900 640 300 120 60 30 20 15 10 5
"""

# Type C, one quadrant (0-90 degrees; Cycles mirrors it to the circle), candela multiplier 2.5,
# ballast factor 0.9, nothing above the horizon.
QUADRANT = """IESNA91
TILT=NONE
1 -1 2.5 6 3 1 1 0 0 0
0.9 1.0 40
0 15 30 45 70 90
0 40 90
500 420 300 180 60 0
500 470 380 260 120 10
500 300 120 60 20 0
"""

# TILT=INCLUDE (its values skipped), horizontal angles 0-270 (Cycles adds the 360 row).
TILTED_NO_360 = """IESNA:LM-63-1995
TILT=INCLUDE
1
3
0 45 90
1.0 0.8 0.5
1 1000 1.0 4 4 1 2 0.3 0.3 0.1
1.0 0.95 60
0 30 60 90
0 90 180 270
700 500 200 50
600 550 250 40
500 300 100 10
650 450 300 60
"""

# Type B (Cycles swaps the axes and mirrors both).
TYPE_B = """IESNA91
TILT=NONE
1 -1 1 4 3 2 1 0 0 0
1.0 1.0 40
0 30 60 90
0 45 90
400 300 200 100
350 250 150 50
300 200 100 20
"""

# Type C, vertical angles 90-180 only (upward light).
UPWARD = """IESNA91
TILT=NONE
1 -1 1 3 1 1 1 0 0 0
1.0 1.0 40
90 135 180
0
300 200 100
"""
