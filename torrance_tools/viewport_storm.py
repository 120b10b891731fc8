# SPDX-License-Identifier: Apache-2.0
"""A seeded storm of random edits of a 3D view and its scene, as a person makes them while the
viewport renders (blender_tests/test_gui_viewport_storm.py).

    storm = ViewportStorm(random.Random(seed), space)      # in a GUI Blender, on a 3D view
    storm.one_edit()       # one random edit (weights in KINDS)
    storm.reset()          # back to the starting state: extra objects removed, Rendered, ...

The scene must have the materials Red, Grey, Blue, the objects Sphere, Sun and Point (a point
light): torrance_tools.testing.sphere_on_floor plus a Blue material and a Point light.
Objects are made and removed through bpy.data (no operators: no undo steps, which would keep
memory for a reason of their own).
"""

import math

import bpy
from mathutils import Euler, Vector

MAX_EXTRA = 3                   # extra objects alive at a time
MATERIALS = ("Red", "Grey", "Blue")
# (edit, weight) of the random choice
KINDS = (("colour", 3), ("roughness", 2), ("add", 2), ("delete", 1), ("move", 3), ("light", 2),
         ("shading", 1), ("camera", 1), ("view", 2), ("border", 1))
CUBE_FACES = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


class ViewportStorm:
    """Random edits of the scene and of the 3D view `space` (a SpaceView3D), drawn from `rng`."""

    def __init__(self, rng, space, shading_type='RENDERED'):
        self.rng = rng
        self.space = space
        self.rv3d = space.region_3d
        self.shading_type = shading_type     # the storm's "on" shading (toggled with SOLID)
        self.scene = bpy.context.scene
        self.materials = [bpy.data.materials[n] for n in MATERIALS]
        self.sun = bpy.data.objects["Sun"]
        self.point = bpy.data.objects["Point"]
        self.extras = []
        self.serial = 0
        self.counts = {}                     # edit kind -> how many were made

    # -- the edits -----------------------------------------------------------------------------
    def one_edit(self):
        kind = self.rng.choices([k for k, _ in KINDS], [w for _, w in KINDS])[0]
        getattr(self, "edit_" + kind)()
        self.counts[kind] = self.counts.get(kind, 0) + 1
        return kind

    def _bsdf(self):
        return self.rng.choice(self.materials).node_tree.nodes["Principled BSDF"]

    def edit_colour(self):
        r = self.rng
        self._bsdf().inputs["Base Color"].default_value = (r.random(), r.random(), r.random(), 1)

    def edit_roughness(self):
        self._bsdf().inputs["Roughness"].default_value = self.rng.random()

    def edit_add(self):
        if len(self.extras) >= MAX_EXTRA:
            return self.edit_delete()
        r = self.rng
        self.serial += 1
        s = 0.2 + 0.3 * r.random()
        verts = [(x * s, y * s, z * s) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
        mesh = bpy.data.meshes.new(f"Extra{self.serial}")
        mesh.from_pydata(verts, [], CUBE_FACES)
        mesh.materials.append(r.choice(self.materials))
        ob = bpy.data.objects.new(f"Extra{self.serial}", mesh)
        ob.location = (r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(0.2, 1.5))
        self.scene.collection.objects.link(ob)
        self.extras.append(ob)

    def edit_delete(self):
        if not self.extras:
            return self.edit_add()
        self._remove(self.extras.pop(self.rng.randrange(len(self.extras))))

    @staticmethod
    def _remove(ob):
        mesh = ob.data
        bpy.data.objects.remove(ob)
        bpy.data.meshes.remove(mesh)

    def edit_move(self):
        r = self.rng
        ob = r.choice([bpy.data.objects["Sphere"], *self.extras])
        ob.location = (r.uniform(-1.5, 1.5), r.uniform(-1.5, 1.5), r.uniform(0.3, 1.5))

    def edit_light(self):
        r = self.rng
        k = r.randrange(4)
        if k == 0:
            self.sun.data.energy = r.uniform(0.5, 5.0)
        elif k == 1:
            self.sun.data.color = (r.random(), r.random(), r.random())
        elif k == 2:
            self.sun.rotation_euler = (r.uniform(0.1, 1.2), 0.0, r.uniform(0, 2 * math.pi))
        else:
            self.point.location = (r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(1, 3))
            self.point.data.energy = r.uniform(50, 500)

    def edit_shading(self):
        shading = self.space.shading
        k = self.rng.randrange(3)
        if k == 0:        # Solid <-> the storm's shading (Rendered: the engine freed and made)
            shading.type = 'SOLID' if shading.type == self.shading_type else self.shading_type
        elif k == 1:
            shading.use_scene_world_render = not shading.use_scene_world_render
        else:
            shading.use_scene_lights_render = not shading.use_scene_lights_render

    def edit_camera(self):
        self.rv3d.view_perspective = 'PERSP' if self.rv3d.view_perspective == 'CAMERA' \
            else 'CAMERA'

    def edit_view(self):
        r = self.rng
        self.rv3d.view_rotation = Euler((r.uniform(0.9, 1.4), 0.0,
                                         r.uniform(-0.6, 0.6))).to_quaternion()
        self.rv3d.view_distance = r.uniform(5.0, 9.0)

    def edit_border(self):
        space = self.space
        if space.use_render_border:
            space.use_render_border = False
            return
        r = self.rng
        x0, y0 = r.uniform(0.0, 0.5), r.uniform(0.0, 0.5)
        space.render_border_min_x, space.render_border_max_x = x0, x0 + r.uniform(0.1, 0.5)
        space.render_border_min_y, space.render_border_max_y = y0, y0 + r.uniform(0.1, 0.5)
        space.use_render_border = True

    # -- the starting state --------------------------------------------------------------------
    def reset(self):
        """Extra objects removed, the storm's shading with the scene's world and lights, no
        render border, the user view looking at the sphere."""
        while self.extras:
            self._remove(self.extras.pop())
        shading = self.space.shading
        shading.type = self.shading_type
        shading.use_scene_world_render = True
        shading.use_scene_lights_render = True
        self.space.use_render_border = False
        rv3d = self.rv3d
        rv3d.view_perspective = 'PERSP'
        rv3d.view_location = Vector((0.0, 0.0, 0.8))
        rv3d.view_rotation = Euler((1.25, 0.0, 0.0)).to_quaternion()
        rv3d.view_distance = 7.0

    def tour(self):
        """Every state the storm can reach, once: the studio HDRI (scene world and lights
        off), camera view, a render border, then each edit three times. Yields after each
        change (the caller waits for the viewport)."""
        shading = self.space.shading
        shading.use_scene_world_render = False
        shading.use_scene_lights_render = False
        yield
        self.reset()
        self.rv3d.view_perspective = 'CAMERA'
        yield
        self.edit_border()
        yield
        self.reset()
        for kind, _ in KINDS:
            for _ in range(3):
                getattr(self, "edit_" + kind)()
                yield
        self.reset()
