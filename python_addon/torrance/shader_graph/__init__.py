"""Blender shader node graphs compiled into programs the core evaluates per hit."""
