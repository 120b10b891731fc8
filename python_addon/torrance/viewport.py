# SPDX-License-Identifier: Apache-2.0
"""The interactive viewport (Rendered shading): to be completed."""


def view_update(engine, context, depsgraph):
    return None


def view_draw(engine, context, depsgraph):
    return None


def free(engine):
    return None
