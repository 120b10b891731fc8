# SPDX-License-Identifier: Apache-2.0
"""How the add-on reads shader trees (no rendering): the closures, weights and factors of nested
Mix/Add Shader trees, the Bump node's arguments, and the reports of what Torrance leaves out
(once per node and material).

Run: scripts/blender -b --factory-startup --python-exit-code 1 \
         --python blender_tests/test_mix_shader_reading.py
"""

import bpy

from torrance_tools import testing
from torrance_tools.scene import node_material
from torrance_tools.testing import check


class DryTextures:
    """Every image 'loads' as texture id 7 (the reader's stand-in for TextureTable)."""

    def texture(self, image, interpolation="Linear"):
        return 7 if image is not None else None


def shader(nodes, kind, **inputs):
    n = nodes.new(kind)
    for name, value in inputs.items():
        n.inputs[name].default_value = value
    return n


def read(mat):
    from torrance.materials import MaterialReader
    from torrance.reporting import Reporter
    reporter = Reporter(None)
    messages = []
    reporter.report = lambda level, text: messages.append((level, text))
    return MaterialReader(reporter, DryTextures()).read(mat), messages


def nested_tree():
    """Mix(Checker, Add(Diffuse, Glossy), Mix(0.3, Principled, Emission))."""
    mat, nodes, links, out = node_material("Nested")
    outer = nodes.new("ShaderNodeMixShader")
    checker = nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 3.0
    checker.inputs["Color1"].default_value = (1.0, 1.0, 1.0, 1.0)
    checker.inputs["Color2"].default_value = (0.5, 0.5, 0.5, 1.0)
    uv = nodes.new("ShaderNodeUVMap")
    links.new(uv.outputs["UV"], checker.inputs["Vector"])
    links.new(checker.outputs["Color"], outer.inputs["Fac"])
    add = nodes.new("ShaderNodeAddShader")
    links.new(shader(nodes, "ShaderNodeBsdfDiffuse", Roughness=0.4).outputs[0], add.inputs[0])
    glossy = shader(nodes, "ShaderNodeBsdfGlossy", Roughness=0.2)
    glossy.distribution = 'BECKMANN'
    links.new(glossy.outputs[0], add.inputs[1])
    inner = nodes.new("ShaderNodeMixShader")
    inner.inputs["Fac"].default_value = 0.3
    links.new(shader(nodes, "ShaderNodeBsdfPrincipled").outputs[0], inner.inputs[1])
    links.new(shader(nodes, "ShaderNodeEmission", Strength=2.0).outputs[0], inner.inputs[2])
    links.new(add.outputs[0], outer.inputs[1])
    links.new(inner.outputs[0], outer.inputs[2])
    links.new(outer.outputs[0], out.inputs["Surface"])
    return mat


def unsupported_tree():
    """Mix(Shader to RGB, Specular BSDF, Diffuse with a Bump from an image) and a checker on
    Generated (read by the shader graph: a program factor)."""
    mat, nodes, links, out = node_material("Unsupported")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(nodes.new("ShaderNodeShaderToRGB").outputs["Alpha"], mix.inputs["Fac"])
    links.new(nodes.new("ShaderNodeEeveeSpecular").outputs[0], mix.inputs[1])
    diffuse = shader(nodes, "ShaderNodeBsdfDiffuse")
    bump = nodes.new("ShaderNodeBump")
    bump.invert = True
    bump.inputs["Distance"].default_value = 0.2
    bump.inputs["Strength"].default_value = 0.7
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = bpy.data.images.new("Height", 4, 4)
    links.new(tex.outputs["Color"], bump.inputs["Height"])
    links.new(bump.outputs["Normal"], diffuse.inputs["Normal"])
    add = nodes.new("ShaderNodeAddShader")
    links.new(diffuse.outputs[0], add.inputs[0])
    mix2 = nodes.new("ShaderNodeMixShader")
    links.new(nodes.new("ShaderNodeTexChecker").outputs["Fac"], mix2.inputs["Fac"])
    links.new(shader(nodes, "ShaderNodeBsdfGlossy").outputs[0], mix2.inputs[1])
    links.new(mix2.outputs[0], add.inputs[1])
    links.new(add.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    return mat


def transparent_mix(fac_node, fac_output):
    """Mix(fac, Principled, tinted Transparent BSDF)."""
    mat, nodes, links, out = node_material(f"TransparentMix{fac_node}")
    mix = nodes.new("ShaderNodeMixShader")
    fac = nodes.new(fac_node)
    if fac_node == "ShaderNodeTexImage":
        fac.image = bpy.data.images.new("Mask", 4, 4)
    else:
        links.new(nodes.new("ShaderNodeTexCoord").outputs["UV"], fac.inputs["Vector"])
    links.new(fac.outputs[fac_output], mix.inputs["Fac"])
    links.new(shader(nodes, "ShaderNodeBsdfPrincipled").outputs[0], mix.inputs[1])
    links.new(shader(nodes, "ShaderNodeBsdfTransparent", Color=(0.2, 0.4, 0.6, 1.0)).outputs[0],
              mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    return mat


def check_transparent_mix():
    """A Transparent BSDF in a Mix Shader becomes the other shader's alpha (transparent_mix.py);
    with a Fac that pattern does not read, the mixture's Transparent closure."""
    args, messages = read(transparent_mix("ShaderNodeTexImage", "Color"))
    print("transparent mix", {k: args.get(k) for k in ("alpha", "alpha_texture",
                                                        "alpha_from_luminance", "alpha_inverted",
                                                        "transparent_color")}, flush=True)
    check("mixture" not in args and args["alpha_texture"] == 7 and args["alpha_from_luminance"]
          and args["alpha_inverted"], f"an image's Color as Fac, Transparent second: {args}")
    check(all(abs(a - b) < 1e-6 for a, b in zip(args["transparent_color"], (0.2, 0.4, 0.6),
                                                 strict=True)),
          f"the Transparent's Color tints: {args['transparent_color']}")
    check(not messages, f"nothing reported: {messages}")
    args, messages = read(transparent_mix("ShaderNodeTexChecker", "Fac"))
    texts = [t for _l, t in messages]
    kinds = [kind for kind, _a, _t in args.get("mixture", {}).get("closures", [])]
    check("transparent" in kinds and not texts,
          f"a checker Fac: a mixture with a Transparent closure, nothing reported: {kinds} {texts}")


def read_surface(mat, nodes, links, out, node, in_mix):
    """`node` at the output's Surface (as_surface), read: the add_material() arguments of its
    closure (in a mix, the first closure's) and the messages."""
    as_surface(nodes, links, out, node, in_mix)
    args, messages = read(mat)
    return (args["mixture"]["closures"][0][1] if in_mix else args), messages


def as_surface(nodes, links, out, node, in_mix):
    """Links `node` to the output's Surface, alone or (in_mix) mixed with a Diffuse BSDF."""
    if not in_mix:
        links.new(node.outputs[0], out.inputs["Surface"])
        return
    mix = nodes.new("ShaderNodeMixShader")
    links.new(node.outputs[0], mix.inputs[1])
    links.new(shader(nodes, "ShaderNodeBsdfDiffuse").outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])


def check_glass_anisotropy():
    """Blender 5.1+'s stretched glass is read, not reported (it was until issue 35's change): the
    Glass BSDF's Anisotropy and Rotation and the Principled's Anisotropic over its transmission
    (transmission_anisotropic, alone and in a mix); 4.x-5.0 (isotropic glass) and an unstretched
    node send none."""
    cases = 0
    for kind, names in (("ShaderNodeBsdfGlass", ("Anisotropy", "Rotation")),
                        ("ShaderNodeBsdfPrincipled", ("Anisotropic", "Anisotropic Rotation"))):
        for in_mix in (False, True):
            for value in (0.0, 0.5):
                mat, nodes, links, out = node_material(f"Stretched{cases}")
                node = nodes.new(kind)
                if names[0] not in node.inputs:      # 3.x/4.x/5.0's Glass
                    break
                if "Transmission Weight" in node.inputs:
                    node.inputs["Transmission Weight"].default_value = 1.0
                elif "Transmission" in node.inputs:
                    node.inputs["Transmission"].default_value = 1.0
                node.inputs[names[0]].default_value = value
                node.inputs[names[1]].default_value = 0.25
                args, messages = read_surface(mat, nodes, links, out, node, in_mix)
                want = value > 0.0 and bpy.app.version >= (5, 1, 0)
                check(bool(args.get("transmission_anisotropic")) == want
                      and (not want or (args.get("anisotropy") == value
                                        and args.get("anisotropic_rotation") == 0.25)),
                      f"{kind} {names[0]} {value} (mix: {in_mix}): {args.get('anisotropy')} "
                      f"{args.get('transmission_anisotropic')}")
                check(not [t for _l, t in messages if "Anisotrop" in t or "isotropic" in t],
                      f"reported: {messages}")
                cases += 1
    print(f"glass anisotropy read: {cases} cases", flush=True)
    if bpy.app.version >= (5, 1, 0):
        check(cases == 8, f"5.1+: {cases} cases, not the Glass's and the Principled's")


def check_thin_wall():
    """Blender 5.x's Thin Wall is read (thin_wall, alone and in a mix) and not reported; off, or
    in a Blender without the input, no thin_wall argument."""
    for in_mix in (False, True):
        for on in (False, True):
            mat, nodes, links, out = node_material(f"Thin{int(in_mix)}{int(on)}")
            node = nodes.new("ShaderNodeBsdfPrincipled")
            has_input = "Thin Wall" in node.inputs
            if has_input:
                node.inputs["Thin Wall"].default_value = on
            args, messages = read_surface(mat, nodes, links, out, node, in_mix)
            want = has_input and on
            check(bool(args.get("thin_wall")) == want and not [t for _l, t in messages
                                                               if "Thin Wall" in t],
                  f"Thin Wall {on} (mix: {in_mix}, input: {has_input}): "
                  f"{args.get('thin_wall')} {messages}")
    if bpy.app.version >= (5, 0, 0):
        check(has_input, "Blender 5.x's Principled has Thin Wall")
    print("thin wall read: 4 cases", flush=True)


def check_dispersion():
    """Blender 5.x's Transmission Dispersion Scale / Abbe Number are read as their quotient
    (dispersion, alone and in a mix) and not reported; none at Scale 0 or without transmission."""
    cases = 0
    for in_mix in (False, True):
        for scale, transmission in ((0.5, 1.0), (0.0, 1.0), (0.5, 0.0)):
            mat, nodes, links, out = node_material(f"Dispersion{cases}")
            node = nodes.new("ShaderNodeBsdfPrincipled")
            if "Transmission Dispersion Scale" not in node.inputs:
                return
            node.inputs["Transmission Weight"].default_value = transmission
            node.inputs["Transmission Dispersion Scale"].default_value = scale
            node.inputs["Transmission Dispersion Abbe Number"].default_value = 25.0
            args, messages = read_surface(mat, nodes, links, out, node, in_mix)
            want = 0.5 / 25.0 if scale > 0.0 and transmission > 0.0 else None
            got = args.get("dispersion")
            check((got is None and want is None) or abs(got - want) < 1e-7,
                  f"dispersion {got}, want {want} (mix: {in_mix}, scale {scale}, "
                  f"transmission {transmission})")
            check(not [t for _l, t in messages if "Dispersion" in t], f"reported: {messages}")
            cases += 1
        # A Scale that varies over the surface: the program computes the quotient.
        mat, nodes, links, out = node_material(f"Dispersion{cases}")
        node = nodes.new("ShaderNodeBsdfPrincipled")
        node.inputs["Transmission Weight"].default_value = 1.0
        links.new(nodes.new("ShaderNodeTexNoise").outputs["Fac"],
                  node.inputs["Transmission Dispersion Scale"])
        args, messages = read_surface(mat, nodes, links, out, node, in_mix)
        check(args.get("dispersion_register", -1) >= 0 and not args.get("dispersion"),
              f"a varying Scale (mix: {in_mix}): {args.get('dispersion_register')} "
              f"{args.get('dispersion')}")
        check(not [t for _l, t in messages if "Dispersion" in t or "varies" in t],
              f"reported: {messages}")
        cases += 1
    print(f"dispersion read: {cases} cases", flush=True)


def check_subsurface_anisotropy():
    """A negative Subsurface Anisotropy is Cycles 5.3's (its new Random Walk); Cycles 4.x and 5.0
    clamp it to 0 (a review finding: 5.0 read it as 5.3)."""
    mat, nodes, links, out = node_material("NegativeAnisotropy")
    node = shader(nodes, "ShaderNodeBsdfPrincipled")
    if "Subsurface Weight" not in node.inputs:      # Blender 3.x: v1's anisotropy, [0, 1]
        return
    node.inputs["Subsurface Weight"].default_value = 1.0
    node.inputs["Subsurface Anisotropy"].default_value = -0.5
    links.new(node.outputs[0], out.inputs["Surface"])
    args, _messages = read(mat)
    got = args.get("subsurface_anisotropy")
    print(f"subsurface anisotropy -0.5 read as {got}", flush=True)
    if bpy.app.version >= (5, 3, 0):
        check(got == -0.5, f"5.3 keeps a negative anisotropy: {got}")
    elif bpy.app.version < (5, 1, 0):
        check(got == 0.0, f"4.x/5.0 clamp the anisotropy to 0: {got}")


def main():
    testing.addon()
    check_transparent_mix()
    check_glass_anisotropy()
    check_thin_wall()
    check_dispersion()
    check_subsurface_anisotropy()
    testing.clear_scene()
    args, messages = read(nested_tree())
    mix = args.get("mixture")
    check(mix is not None, f"a nested tree reads as a mixture: {args}")
    kinds = [(kind, terms) for kind, _a, terms in mix["closures"]]
    factors = mix["factors"]
    print("closures", kinds, "factors", factors, flush=True)
    check(factors[0] == dict(kind="checker", scale=3.0, color1=1.0, color2=0.5),
          f"the checker's Color output gives the colours' luminances: {factors[0]}")
    check([f["kind"] for f in factors[1:]] == ["constant", "constant"]
          and abs(factors[1]["value"] - 0.7) < 1e-6 and abs(factors[2]["value"] - 0.3) < 1e-6,
          f"the constant Mix factor becomes (1 - fac) and fac: {factors[1:]}")
    rough_diffuse = "diffuse_energy_preserving" if bpy.app.version >= (4, 3, 0) else "diffuse"
    check(kinds == [(rough_diffuse, [-1]), ("glossy", [-1]), ("principled", [0, 1]),
                    ("emission", [0, 2])], f"closures and weight terms: {kinds}")
    diffuse = mix["closures"][0][1]
    check(abs(diffuse["roughness"] - 0.4) < 1e-6 and diffuse["specular"] == 0.0,
          f"the Diffuse BSDF's roughness is read: {diffuse}")
    check(mix["closures"][3][1]["emission_strength"] == 2.0, "the Emission's strength")
    texts = [t for _l, t in messages]
    check(mix["closures"][1][1].get("distribution") == 'BECKMANN'
          and not any("Beckmann" in t for t in texts),
          f"the Glossy's Beckmann distribution is read, not reported: "
          f"{mix['closures'][1][1].get('distribution')}, {texts}")

    args, messages = read(unsupported_tree())
    mix = args["mixture"]
    texts = [t for _l, t in messages]
    print("\n".join(texts), flush=True)
    kinds = [(kind, terms) for kind, _a, terms in mix["closures"]]
    # Fac from a Shader to RGB: the socket's 0.5 (a constant: 0.5 and 0.5);
    # the Specular BSDF left out; the checker on Generated coordinates a program factor of the
    # mixture's shader program.
    check(kinds[0][0] == "diffuse" and len(kinds) == 2 and kinds[1][0] == "glossy",
          f"Specular BSDF left out, Diffuse and Glossy kept: {kinds}")
    normal = mix["normal"]
    check(normal.get("bump_texture") == 7 and abs(normal.get("bump_strength", 0) - 0.7) < 1e-6
          and abs(normal.get("bump_distance", 0) + 0.2) < 1e-6,
          f"the Bump node's arguments (Invert negates Distance): {normal}")
    check([f["kind"] for f in mix["factors"]] == ["constant", "program"] and "shader_program" in mix
          and ('generated',) in mix["program_attributes"],
          f"the checker on Generated: a program factor reading Generated: {mix['factors']}")
    for expected in ("'Shader to RGB' is not supported",
                     "the shader 'Specular BSDF' is not supported in a mix",
                     "'Glossy BSDF' has another Normal than 'Diffuse BSDF'"):
        hits = [t for t in texts if expected in t]
        check(len(hits) == 1, f"reported once: {expected!r} in {texts}")
        check(hits[0].startswith("Material 'Unsupported':"), f"names the material: {hits[0]}")


testing.run(main)
