# SPDX-License-Identifier: Apache-2.0
"""The native module torrance_core, loaded once on first use (render, export and viewport
import it from here; tools and tests may put a proxy in `_core`)."""

import importlib.util

_core = None
_core_error = None


class CoreMissing(RuntimeError):
    pass


def load_core():
    """The native module torrance_core; raises RuntimeError with a clear message if missing."""
    global _core, _core_error
    if _core is None:
        try:
            if importlib.util.find_spec(f"{__package__}.torrance_core") is not None:
                from . import torrance_core      # bundled: build/addon, the legacy add-on zip
            else:
                import torrance_core             # the Blender 4.2+ extension: from its wheel
        except Exception as exc:             # ImportError, or a broken .so (OSError, ...)
            _core_error = f"{type(exc).__name__}: {exc}"
            raise CoreMissing(
                "Torrance's native module 'torrance_core' could not be loaded "
                f"({_core_error}). Rebuild the add-on (scripts/build) and reinstall it.") from exc
        _core = torrance_core
        _core_error = None
    return _core
