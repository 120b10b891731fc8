# A/B and profiling driver: exports each scene via the add-on, then renders it with core.render
# repeatedly, alternating os.environ TORRANCE_AB_OLD (read by the core per render) when --ab.
import os, sys, time, statistics, hashlib
import numpy as np
from torrance_tools import comparison_scenes, addon_access
import bpy
argv = sys.argv[sys.argv.index("--") + 1:]
mode = argv[0]; reps = int(argv[1]); spp = int(argv[2]); names = argv[3:] or list(comparison_scenes.SCENES)
mod = addon_access.addon(); core = mod.render.load_core()
def capture(name):
    scene, _ = comparison_scenes.build(name)
    got = {}
    def r(tc_scene, settings, **kw):
        got["s"] = tc_scene; got["set"] = settings
        return core.render(tc_scene, settings, **kw)
    proxy = addon_access.core_proxy(core); proxy.render = r
    mod.render._core = proxy
    scene.render.engine = 'TORRANCE'; scene.torrance.samples = 1
    try:
        bpy.ops.render.render(write_still=False, scene=scene.name)
    finally:
        mod.render._core = core
    return got["s"], got["set"]
def digest(res):
    for attr in ("pixels", "image", "rgba"):
        if hasattr(res, attr):
            return hashlib.sha256(np.ascontiguousarray(np.asarray(getattr(res, attr), dtype=np.float32)).tobytes()).hexdigest()[:16]
    return "?"
for name in names:
    s, st = capture(name); st.samples = spp
    if hasattr(st, "threads"): st.threads = 1
    times = {"old": [], "new": []}; hashes = {}
    for i in range(reps):
        order = ("old", "new") if i % 2 == 0 else ("new", "old")
        if mode != "ab": order = ("new",)
        for v in order:
            if v == "old": os.environ["TORRANCE_AB_OLD"] = "1"
            else: os.environ.pop("TORRANCE_AB_OLD", None)
            res = core.render(s, st)
            times[v].append(res.seconds - res.setup_seconds); hashes.setdefault(v, set()).add(digest(res))
    os.environ.pop("TORRANCE_AB_OLD", None)
    if mode == "ab":
        ratios = [n / o for n, o in zip(times["new"], times["old"])]
        print(f"AB {name}: new/old median {statistics.median(ratios):.3f} min {min(ratios):.3f} max {max(ratios):.3f} "
              f"old {statistics.median(times['old']):.3f}s hashes old {hashes['old']} new {hashes['new']}", flush=True)
    else:
        print(f"RUN {name}: {statistics.median(times['new']):.3f}s {hashes['new']}", flush=True)
