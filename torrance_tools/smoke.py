# SPDX-License-Identifier: Apache-2.0
"""A smoke (or fire) simulated with Blender's fluid simulation for the volume tests: a gas domain
with Quick Smoke's material (a Principled Volume of Density 5; Blackbody Intensity 1 for fire)
and an inflow sphere, simulated in Replay mode into the test's temporary cache directory."""

from torrance_tools import scene as make
from torrance_tools import testing


def quick_smoke_material(name, fire=False):
    """Quick Smoke's material: a Principled Volume of Density 5 (and blackbody for fire)."""
    mat, nodes, links, output = make.node_material(name)
    principled = nodes.new('ShaderNodeVolumePrincipled')
    principled.inputs["Density"].default_value = 5.0
    if fire:
        principled.inputs["Blackbody Intensity"].default_value = 1.0
    links.new(principled.outputs[0], output.inputs["Volume"])
    return mat


def smoke_domain(scene, centre, rotation_z_deg=0.0, frames=8, resolution=24, fire=False):
    """A 2 m domain at centre with the smoke of `frames` frames (the scene then at the last);
    returns (domain object, emitter object, cache directory)."""
    domain = make.box(scene, "Domain", centre, (2.0, 2.0, 2.0),
                      quick_smoke_material("Smoke", fire), rotation_z_deg=rotation_z_deg)
    fluid = domain.modifiers.new("Fluid", 'FLUID')
    fluid.fluid_type = 'DOMAIN'
    settings = fluid.domain_settings
    settings.domain_type = 'GAS'
    settings.resolution_max = resolution
    settings.cache_type = 'REPLAY'
    settings.cache_directory = testing.tempdir()
    emitter = make.sphere_object(scene, "Emitter", (centre[0], centre[1], centre[2] - 0.65), 0.3,
                                 None, segments=16, rings=8)
    flow = emitter.modifiers.new("Fluid", 'FLUID')
    flow.fluid_type = 'FLOW'
    flow.flow_settings.flow_type = 'BOTH' if fire else 'SMOKE'
    flow.flow_settings.flow_behavior = 'INFLOW'
    emitter.hide_render = True
    for frame in range(1, frames + 1):
        scene.frame_set(frame)
    return domain, emitter, settings.cache_directory


def attribute_ignored(socket_name):
    """A fault for the volume tests: a wrapper of VolumeReader._grid that ignores the grid a
    Principled Volume's `socket_name` (e.g. "Density Attribute") names."""
    def wrap(original):
        def fault(self, node, name, kind):
            return None if name == socket_name else original(self, node, name, kind)
        return fault
    return wrap
