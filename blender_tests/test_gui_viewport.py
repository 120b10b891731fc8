# SPDX-License-Identifier: Apache-2.0
"""Torrance in Blender's GUI, as an artist uses it: Rendered shading in the 3D viewport,
edits while it refines, camera view (also of a panoramic camera, against Cycles' viewport), a
material preview, and the Properties panels.

Run (as CTest does) in background Blender; it then
1. builds a small scene (red sphere on a grey floor, sun, 0.18 grey world) and saves it;
2. starts an X server (Xvfb, software OpenGL: Mesa llvmpipe) and Blender's GUI on that file,
   with this same script as the driver (bpy.app.timers steps through the checks);
3. reads the driver's results and screenshots and checks them.

No X server (Xvfb missing or unable to start): prints SKIPPED and exits with 77 (CTest:
SKIP_RETURN_CODE 77). TORRANCE_XVFB names the Xvfb binary (default: Xvfb on PATH). Screenshots
are kept in build/test_gui_viewport/ (or $TORRANCE_GUI_SHOTS) and their paths printed.
"""

import json
import math
import os
import sys
import time

import bpy
from torrance_tools import gui

SKIP_CODE = 77
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


# ============================================================================================
# The GUI side (Blender with a window): the driver

def _driver(result_path, shots_dir):
    import numpy as np
    from bpy_extras import view3d_utils

    import torrance
    viewport = torrance.viewport

    results = {"checks": [], "shots": {}, "errors": []}
    t_start = time.perf_counter()

    def log(*args):
        print("gui-driver:", *args, flush=True)

    def view3d():
        win = bpy.context.window_manager.windows[0]
        for area in win.screen.areas:
            if area.type == 'VIEW_3D':
                region = next(r for r in area.regions if r.type == 'WINDOW')
                return win, area, area.spaces.active, region
        raise RuntimeError("no 3D view in the window")

    def screenshot(name):
        win, area, space, region = view3d()
        path = os.path.join(shots_dir, name + ".png")
        with bpy.context.temp_override(window=win, area=area, region=region):
            bpy.ops.screen.screenshot(filepath=path)
        img = bpy.data.images.load(path, check_existing=False)
        w, h = img.size
        buf = np.empty(w * h * img.channels, dtype=np.float32)
        img.pixels.foreach_get(buf)
        bpy.data.images.remove(img)
        pixels = buf.reshape(h, w, -1)[:, :, :3] * 255.0      # row 0 = bottom, as Blender
        results["shots"][name] = path
        log(f"screenshot {path}")
        return pixels

    def screenshot_window(name):
        win = bpy.context.window_manager.windows[0]
        path = os.path.join(shots_dir, name + ".png")
        with bpy.context.temp_override(window=win):
            bpy.ops.screen.screenshot(filepath=path)
        results["shots"][name] = path

    def region_pixel(pixels, region, x, y, radius=3):
        """Mean colour around region coordinates (x, y) (origin bottom-left of the region)."""
        wx, wy = int(region.x + x), int(region.y + y)
        patch = pixels[wy - radius:wy + radius + 1, wx - radius:wx + radius + 1]
        return [float(v) for v in patch.reshape(-1, 3).mean(axis=0)]

    def sphere_fit(pixels, region, channel):
        """(centre x, centre y, radius) in region pixels of the pixels where colour `channel`
        (0 red, 1 green) dominates: the rendered sphere's silhouette."""
        sub = pixels[region.y:region.y + region.height, region.x:region.x + region.width]
        main = sub[:, :, channel]
        other = sub[:, :, 1 - channel]
        mask = (main > 90) & (main > 2.0 * other) & (main > 2.0 * sub[:, :, 2])
        ys, xs = np.nonzero(mask)
        if len(xs) < 20:
            return None
        return (float(xs.mean()) + 0.5, float(ys.mean()) + 0.5, float(np.sqrt(len(xs) / np.pi)))

    def check_silhouette(name, pixels, region, channel, radius_world=0.8):
        """The rendered sphere sits where Blender projects it, at the projected size."""
        fit = sphere_fit(pixels, region, channel)
        win, area, space, region_ = view3d()
        rv3d = space.region_3d
        c = project(sphere_center)
        right = rv3d.view_rotation @ Vector((1.0, 0.0, 0.0))
        edge = project(tuple(Vector(sphere_center) + right * radius_world))
        if fit is None or c is None or edge is None:
            check(name, False, f"sphere not found (fit {fit}, projection {c})")
            return
        r_proj = float(np.hypot(edge[0] - c[0], edge[1] - c[1]))
        dist = float(np.hypot(fit[0] - c[0], fit[1] - c[1]))
        ok = dist < 2.0 + 0.03 * r_proj and abs(fit[2] - r_proj) < 2.0 + 0.05 * r_proj
        results.setdefault("silhouettes", {})[name] = dict(
            rendered=fit, projected=(c[0], c[1], r_proj))
        check(name, ok, f"rendered centre ({fit[0]:.1f}, {fit[1]:.1f}) radius {fit[2]:.1f} px; "
                        f"Blender projects ({c[0]:.1f}, {c[1]:.1f}) radius {r_proj:.1f} px")

    def project(point):
        win, area, space, region = view3d()
        co = view3d_utils.location_3d_to_region_2d(region, space.region_3d, point)
        return (float(co.x), float(co.y)) if co is not None else None

    def check(name, ok, detail):
        results["checks"].append({"name": name, "ok": bool(ok), "detail": detail})
        log(("ok  " if ok else "FAIL"), name, detail)

    def wait_samples(min_samples, timeout):
        """Yields until the viewport render reached min_samples at full resolution."""
        end = time.perf_counter() + timeout
        while time.perf_counter() < end:
            st = viewport.last_stats
            levels = st.get("levels") or []
            if st.get("error"):
                break
            if levels and st.get("level") == len(levels) - 1 \
                    and st.get("samples_done", 0) >= min(min_samples, st.get("samples_total", 1)):
                break
            yield 0.1
        yield 0.3                    # one more redraw so the newest image is on screen

    sphere_center = (0.0, 0.0, 0.8)
    from mathutils import Euler, Vector

    def cycles_screenshot(name, sub):
        """Cycles' viewport image of the same view (a screenshot `name`), then Torrance again.
        Cycles has no stats to poll: it has finished its samples when its image stops changing
        (two screenshots 2 s apart alike in `sub`, the region) after it has shown one (the
        viewport is a flat grey while Cycles loads; std over the region's middle < 5: the whole
        region's std counts the camera frame's passepartout), however loaded the machine is."""
        win, area, space, region = view3d()
        scene = bpy.context.scene
        scene.render.engine = 'CYCLES'
        mid = (slice(region.y + region.height // 4, region.y + 3 * region.height // 4),
               slice(region.x + region.width // 4, region.x + 3 * region.width // 4))
        pixels, end = None, time.perf_counter() + 180.0
        while time.perf_counter() < end:
            yield 2.0
            previous, pixels = pixels, screenshot(name)
            if previous is not None and np.array_equal(previous[sub], pixels[sub]) \
                    and pixels[mid].std() > 5.0:
                break
        scene.render.engine = 'TORRANCE'
        return pixels

    def check_like_cycles(key, label, torrance_px, cycles_px):
        """Checks (as `label`, results[key]) that two screenshots' regions agree: |Torrance -
        Cycles| of their grey's 8x8 block means (the two renders' noise averages out) below 2.5
        on average and 8 at the 95th percentile (of 255), brightness within 3 %."""
        a, b = torrance_px.mean(axis=2), cycles_px.mean(axis=2)
        hh, ww = (a.shape[0] // 8) * 8, (a.shape[1] // 8) * 8
        blocks = lambda x: x[:hh, :ww].reshape(hh // 8, 8, ww // 8, 8).mean(axis=(1, 3))  # noqa: E731
        diff = np.abs(blocks(a) - blocks(b))
        ratio = float(a.mean() / max(b.mean(), 1e-6))
        results[key] = dict(mean=float(diff.mean()), p95=float(np.percentile(diff, 95)),
                            brightness_ratio=ratio)
        check(label, diff.mean() < 2.5 and np.percentile(diff, 95) < 8.0 and abs(ratio - 1) < 0.03,
              f"|Torrance - Cycles| of 8x8 block means: mean {diff.mean():.2f}, 95th percentile "
              f"{np.percentile(diff, 95):.2f} (of 255); brightness ratio {ratio:.4f}")

    def steps():
        win, area, space, region = view3d()
        scene = bpy.context.scene
        # Frame the scene: a fixed user view looking at the sphere.
        rv3d = space.region_3d
        rv3d.view_perspective = 'PERSP'
        rv3d.view_location = Vector((0.0, 0.0, 0.8))
        rv3d.view_rotation = Euler((1.25, 0.0, 0.0)).to_quaternion()
        rv3d.view_distance = 7.0
        space.overlay.show_overlays = False            # clean pixels: no overlays,
        space.show_gizmo = False                       # no navigation gizmo
        yield 0.5

        # -- Solid mode: the sphere is the grey default viewport colour
        space.shading.type = 'SOLID'
        yield 0.5
        pixels = screenshot("1_solid")
        c = project(sphere_center)
        solid = region_pixel(pixels, region, *c)
        results["solid_sphere"] = solid

        # -- Rendered shading with Torrance
        t0 = time.perf_counter()
        space.shading.type = 'RENDERED'
        yield from wait_samples(8, 60)
        results["switch_to_8_samples_seconds"] = time.perf_counter() - t0
        stats = dict(viewport.last_stats)
        results["stats_rendered"] = stats
        pixels = screenshot("2_rendered_red")
        c = project(sphere_center)
        red = region_pixel(pixels, region, *c)
        # The sky above the floor's far edge (the view looks slightly down at the floor).
        background = region_pixel(pixels, region, region.width * 0.3, region.height * 0.88)
        results["rendered_sphere"] = red
        results["rendered_background"] = background
        check("rendered sphere is red",
              red[0] > 90 and red[0] > 2.0 * red[1] and red[0] > 2.0 * red[2],
              f"sphere pixel {red}, solid mode {solid}")
        check_silhouette("user view: sphere where Blender projects it", pixels, region, 0)
        check("rendered differs from solid", abs(red[0] - solid[0]) + abs(red[1] - solid[1]) > 60,
              f"{red} vs {solid}")
        # World 0.18, Standard view transform: 118/255 when the viewport is colour managed.
        check("background colour managed (0.18 -> ~118)",
              background is not None and all(abs(v - 118) <= 8 for v in background),
              f"background {background}")
        check("first image drawn", stats.get("engine_first_draw_seconds") is not None,
              f"engine created -> first image drawn {stats.get('engine_first_draw_seconds')} s, "
              f"restart -> first draw {stats.get('first_draw_seconds')} s")

        # -- Selecting an object changes nothing rendered: no restart
        restarts = stats.get("restarts")
        builds = stats.get("scene_builds")
        floor = bpy.data.objects["Floor"]
        floor.select_set(True)
        bpy.context.view_layer.objects.active = floor
        yield 0.5
        st = dict(viewport.last_stats)
        check("selection does not restart", st.get("restarts") == restarts and
              st.get("scene_builds") == builds,
              f"restarts {restarts} -> {st.get('restarts')}, "
              f"builds {builds} -> {st.get('scene_builds')}")

        # -- Material edit while refining: the sphere turns green, no mesh is re-read
        updates = stats.get("scene_updates")
        mat = bpy.data.materials["Red"]
        base_color = mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"]
        base_color.default_value = (0.02, 0.6, 0.02, 1)
        yield 0.2
        yield from wait_samples(4, 60)
        st = dict(viewport.last_stats)
        pixels = screenshot("3_rendered_green")
        green = region_pixel(pixels, region, *project(sphere_center))
        results["green_sphere"] = green
        check("material edit shows", green[1] > 70 and green[1] > 2.0 * green[0],
              f"sphere pixel {green}")
        check("material edit updated the scene in place without reading meshes",
              st.get("scene_builds") == builds and st.get("scene_updates", 0) > updates
              and st.get("build_meshes_read") == 0,
              f"builds {builds} -> {st.get('scene_builds')}, updates {updates} -> "
              f"{st.get('scene_updates')}, meshes read {st.get('build_meshes_read')}")

        # -- Moving the object: transform only, no mesh read, the scene updated in place
        builds, updates = st.get("scene_builds"), st.get("scene_updates")
        sphere = bpy.data.objects["Sphere"]
        sphere.location.x += 0.3
        yield 0.3
        yield from wait_samples(2, 60)
        st = dict(viewport.last_stats)
        check("moving an object re-uses its cached mesh",
              st.get("build_meshes_read") == 0,
              f"meshes read {st.get('build_meshes_read')}")
        check("moving an object updates the scene in place (no rebuild)",
              st.get("scene_builds") == builds and st.get("scene_updates", 0) > updates
              and st.get("build_kind") == "update" and st.get("build_moved") == 1,
              f"builds {builds} -> {st.get('scene_builds')}, updates {updates} -> "
              f"{st.get('scene_updates')}, last {st.get('build_kind')}")
        sphere.location.x -= 0.3
        yield 0.3

        # -- Changing the view restarts the render, without rebuilding the scene
        yield from wait_samples(2, 60)
        st = dict(viewport.last_stats)
        restarts, builds = st.get("restarts"), st.get("scene_builds")
        rv3d.view_distance = 6.0
        yield 0.5
        st = dict(viewport.last_stats)
        check("view change restarts without rebuilding",
              st.get("restarts", 0) > restarts and st.get("scene_builds") == builds,
              f"restarts {restarts} -> {st.get('restarts')}, "
              f"builds {builds} -> {st.get('scene_builds')}")
        results["view_change_first_draw_seconds"] = st.get("first_draw_seconds")

        # -- A render border (Ctrl+B) through the middle of the sphere: only its left half
        c = project(sphere_center)
        space.use_render_border = True
        space.render_border_min_x, space.render_border_max_x = 0.0, c[0] / region.width
        space.render_border_min_y, space.render_border_max_y = 0.0, 1.0
        yield 0.3
        yield from wait_samples(2, 60)
        pixels = screenshot("4a_render_border")
        left = region_pixel(pixels, region, c[0] - 25, c[1])
        right = region_pixel(pixels, region, c[0] + 25, c[1])
        check("render border: rendered inside only",
              left[1] > 2 * left[0] and not right[1] > 1.5 * right[0],
              f"inside {left}, outside {right}")
        space.use_render_border = False
        yield 0.3

        # -- Orthographic user view (the core's orthographic camera)
        rv3d.view_perspective = 'ORTHO'
        yield 0.3
        yield from wait_samples(2, 60)
        pixels = screenshot("4_ortho_view")
        check_silhouette("orthographic view: sphere where Blender projects it", pixels, region, 1)
        rv3d.view_perspective = 'PERSP'

        # -- Camera view: the scene camera with Blender's camera-view zoom and offset
        rv3d.view_perspective = 'CAMERA'
        rv3d.view_camera_zoom = 10.0
        rv3d.view_camera_offset = (0.05, -0.03)
        yield 0.3
        yield from wait_samples(4, 60)
        pixels = screenshot("4_camera_view")
        check_silhouette("camera view (zoom, offset): sphere where Blender projects it",
                         pixels, region, 1)
        green = region_pixel(pixels, region, *project(sphere_center))
        results["camera_view_sphere"] = green
        check("camera view shows the sphere where Blender projects it",
              green[1] > 70 and green[1] > 2.0 * green[0], f"sphere pixel {green}")

        # -- The viewport's studio HDRI (Scene World off), as Cycles shows it
        shading = space.shading
        shading.use_scene_world_render = False
        shading.use_scene_lights_render = False
        shading.studio_light = 'forest.exr'
        shading.studiolight_rotate_z = 1.0
        shading.studiolight_background_alpha = 1.0
        yield 0.3
        yield from wait_samples(16, 90)
        torrance_px = screenshot("4b_studio_torrance")
        sub = (slice(region.y, region.y + region.height), slice(region.x, region.x + region.width))
        cycles_px = yield from cycles_screenshot("4c_studio_cycles", sub)
        check_like_cycles("studio_vs_cycles",
                          "studio HDRI world as Cycles shows it (rotation, strength)",
                          torrance_px[sub], cycles_px[sub])
        shading.use_scene_world_render = True
        shading.use_scene_lights_render = True
        yield 0.5

        # -- Camera view of a panoramic camera (Fisheye Equidistant, 180 degrees, shifted), with
        # the camera-view zoom and offset above: the panorama mapped onto the drawn camera frame
        cam = scene.camera.data
        owner = cam if hasattr(cam, "panorama_type") else cam.cycles    # 4.x+ / 3.x
        cam.type = 'PANO'
        cam.shift_x = 0.1
        owner.panorama_type = 'FISHEYE_EQUIDISTANT'
        owner.fisheye_fov = math.pi
        yield 0.3
        yield from wait_samples(16, 90)
        torrance_px = screenshot("4d_panoramic_torrance")
        cycles_px = yield from cycles_screenshot("4e_panoramic_cycles", sub)
        check_like_cycles("panoramic_vs_cycles",
                          "camera view of a panoramic camera as Cycles shows it",
                          torrance_px[sub], cycles_px[sub])
        cam.type = 'PERSP'
        cam.shift_x = 0.0
        yield 0.3

        # -- Leave Rendered mode: the engine is freed and its render thread stopped
        space.shading.type = 'SOLID'
        for _ in range(30):
            yield 0.1
            if viewport.open_states() == 0:
                break
        check("leaving Rendered mode stops the render",
              viewport.open_states() == 0 and viewport.running_renders() == 0,
              f"{viewport.open_states()} viewport states open, "
              f"{viewport.running_renders()} render threads running")

        # -- Properties editor (maximised): Torrance's panels draw without errors
        props = next(a for a in win.screen.areas if a.type == 'PROPERTIES')
        sphere = bpy.data.objects["Sphere"]
        for ob in bpy.context.view_layer.objects:
            ob.select_set(ob == sphere)
        bpy.context.view_layer.objects.active = sphere
        with bpy.context.temp_override(window=win, area=props,
                                       region=next(r for r in props.regions if r.type == 'WINDOW')):
            bpy.ops.screen.screen_full_area()
        yield 0.3
        for tab in ("RENDER", "MATERIAL", "WORLD"):
            full = next(a for a in win.screen.areas if a.type == 'PROPERTIES')
            full.spaces.active.context = tab
            full.tag_redraw()
            yield 0.5
            screenshot_window(f"5_properties_{tab.lower()}")
        sun = bpy.data.objects["Sun"]
        for ob in bpy.context.view_layer.objects:
            ob.select_set(ob == sun)
        bpy.context.view_layer.objects.active = sun
        full = next(a for a in win.screen.areas if a.type == 'PROPERTIES')
        full.spaces.active.context = 'DATA'
        full.tag_redraw()
        yield 0.5
        screenshot_window("5_properties_light")
        full = next(a for a in win.screen.areas if a.type == 'PROPERTIES')
        with bpy.context.temp_override(window=win, area=full,
                                       region=next(r for r in full.regions if r.type == 'WINDOW')):
            bpy.ops.screen.back_to_previous()
        yield 0.3
        win, area, space, region = view3d()

        # -- Material preview (thumbnail) rendered by Torrance
        t0 = time.perf_counter()
        with bpy.context.temp_override(window=win, area=area, region=region, id=mat):
            bpy.ops.ed.lib_id_generate_preview()
        preview = mat.preview
        px = None
        end = time.perf_counter() + 60
        # The preview job writes its image as it renders: read it once the job has run and ended
        # (the first pixels alone were once a strip at the bottom, the centre still black).
        seen_running = False
        while time.perf_counter() < end:
            running = bpy.app.is_job_running('RENDER_PREVIEW')
            seen_running |= running
            w, h = preview.image_size
            if w and h and not running and (seen_running or time.perf_counter() - t0 > 2.0):
                buf = np.empty(w * h * 4, dtype=np.float32)
                preview.image_pixels_float.foreach_get(buf)
                if buf.any():
                    px = buf.reshape(h, w, 4)
                    break
            yield 0.2
        results["preview_seconds"] = time.perf_counter() - t0
        if px is None:
            check("material preview rendered", False, "no preview pixels after 60 s")
        else:
            h, w = px.shape[:2]
            centre = px[h // 2 - 4:h // 2 + 4, w // 2 - 4:w // 2 + 4, :3]
            centre = centre.reshape(-1, 3).mean(axis=0)
            results["preview_centre"] = [float(v) for v in centre]
            results["preview_size"] = [w, h]
            check("material preview is green", centre[1] > 1.5 * centre[0] and centre[1] > 0.1,
                  f"{w}x{h}, centre {centre}")
            # Keep it as a picture too.
            img = bpy.data.images.new("preview", w, h, alpha=True)
            img.pixels.foreach_set(px.reshape(-1))
            img.filepath_raw = os.path.join(shots_dir, "7_material_preview.png")
            img.file_format = 'PNG'
            img.save()
            results["shots"]["7_material_preview"] = img.filepath_raw

    gui.drive_to_json(steps(), results, result_path, t_start, log)


# ============================================================================================
# The background side (CTest): scene, X server, GUI run, verdict

def _build_scene(path):
    from torrance_tools import testing
    scene = testing.clear_scene()
    testing.setup_render(scene, width=160, height=120, samples=16)
    scene.torrance.viewport_samples = 16
    scene.cycles.preview_samples = 16                 # for the studio HDRI comparison
    scene.cycles.use_preview_denoising = False
    scene.cycles.use_preview_adaptive_sampling = False
    testing.sphere_on_floor(scene, (0.8, 0.02, 0.02))
    bpy.ops.wm.save_as_mainfile(filepath=path)


def _main():
    build = os.environ.get("TORRANCE_BUILD_DIR", os.path.join(ROOT, "build"))
    shots = os.environ.get("TORRANCE_GUI_SHOTS", os.path.join(build, "test_gui_viewport"))
    os.makedirs(shots, exist_ok=True)
    blend = os.path.join(shots, "scene.blend")
    result_path = os.path.join(shots, "results.json")
    for name in os.listdir(shots):                  # no stale results or screenshots
        if name.endswith(".png") or name == "results.json":
            os.remove(os.path.join(shots, name))
    _build_scene(blend)

    log_path = os.path.join(shots, "blender_gui.log")
    with gui.xvfb() as display:
        if display is None:
            print("SKIPPED: no X server for the GUI test", flush=True)
            sys.exit(SKIP_CODE)
        code, seconds = gui.run_blender(display, blend, __file__,
                                        ["--gui-driver", result_path, shots], log_path,
                                        timeout=400)

    with open(log_path) as f:
        log_text = f.read()
    if not os.path.exists(result_path):
        print(log_text[-6000:])
        if "GLX" in log_text and "Unable to" in log_text or "failed to create" in log_text.lower() \
                and "context" in log_text.lower():
            print(f"SKIPPED: Blender could not open an OpenGL window on Xvfb (see {log_path})")
            sys.exit(SKIP_CODE)
        raise SystemExit(f"FAILED: the GUI run ended ({code}) without results; log {log_path}")
    with open(result_path) as f:
        results = json.load(f)

    print(f"GUI run: {seconds:.1f} s (exit {code}); log {log_path}")
    for name, path in sorted(results["shots"].items()):
        print(f"screenshot {name}: {path}")
    st = results.get("stats_rendered", {})
    print(f"first image: engine created -> drawn {st.get('engine_first_draw_seconds')} s; "
          f"start -> first image {st.get('first_image_seconds')} s; "
          f"full resolution {st.get('full_image_seconds')} s "
          f"at {st.get('width')}x{st.get('height')}")
    print(f"view change -> first draw {results.get('view_change_first_draw_seconds')} s; "
          f"material preview {results.get('preview_seconds')} s")
    failures = [c for c in results["checks"] if not c["ok"]]
    for c in results["checks"]:
        print(("ok    " if c["ok"] else "FAIL  ") + c["name"] + ": " + c["detail"])
    tracebacks = log_text.count("Traceback (most recent call last)")
    if results["errors"]:
        print("driver errors:\n" + "\n".join(results["errors"]))
    if tracebacks:
        print(log_text[-6000:])
    if failures or results["errors"] or tracebacks or len(results["checks"]) < 17:
        print(f"FAILED: {len(failures)} failed checks, {len(results['errors'])} driver errors, "
              f"{tracebacks} Python tracebacks in the GUI log ({log_path})")
        sys.exit(1)
    print(f"PASSED: {len(results['checks'])} checks")
    sys.exit(0)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if "--gui-driver" in argv:
        i = argv.index("--gui-driver")
        _driver(argv[i + 1], argv[i + 2])
    else:
        from torrance_tools import testing
        testing.run(_main)
