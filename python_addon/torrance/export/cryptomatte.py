"""Cryptomatte as Cycles 3.4 writes it: the view layer's Object, Material and Asset layers and
Levels, an entry per object (its name and its asset's, the top-most parent's name), the ids
(the core's cryptomatte_hash: MurmurHash3 as Cryptomatte's float) and the manifests that
Blender's Cryptomatte node reads from the render result's metadata."""

import json

from ..passes import cryptomatte_layers

DEFAULT_SURFACE = "default_surface"     # Cycles' shader of objects without a material


def asset_name(obj):
    """Cycles' asset of an object: its top-most parent's name, or its own."""
    top = obj
    while top.parent is not None:
        top = top.parent
    return top.name


def metadata(view_layer_name, layer, names, tc):
    """The render result's fields of one layer's manifest, as Cycles stamps them:
    cryptomatte/<7 hex digits of the hash of '<view layer>.<layer>'>/name, hash, conversion and
    manifest ({name: 8 hex digits of its hash})."""
    full = f"{view_layer_name}.{layer}"
    prefix = f"cryptomatte/{tc.cryptomatte_hash(full)[0]:08x}"[:-1] + "/"   # 7 of its digits
    manifest = json.dumps({n: f"{tc.cryptomatte_hash(n)[0]:08x}" for n in names},
                          separators=(",", ":"))
    return {prefix + "name": full, prefix + "hash": "MurmurHash3_32",
            prefix + "conversion": "uint32_to_float32", prefix + "manifest": manifest}


class CryptomatteIds:
    """Object entries for a tc.Scene (entry(obj): -1 when the view layer has no Cryptomatte),
    sent with the materials' ids by send()."""

    def __init__(self, tc, tc_scene, view_layer):
        self.tc = tc
        self.scene = tc_scene
        self.view_layer = view_layer
        self.layers = cryptomatte_layers(view_layer) if view_layer is not None else []
        self.entries = {}           # (object name, asset name) -> entry
        self.material_names = {}    # core material index -> name

    def entry(self, obj):
        if not self.layers:
            return -1
        key = (obj.name, asset_name(obj))
        return self.entries.setdefault(key, len(self.entries))

    def send(self, materials):
        """Scene.set_cryptomatte with the entries' and the materials' ids; the render result's
        metadata of the layers ({} without Cryptomatte)."""
        if not self.layers:
            return {}
        hash_id = lambda name: self.tc.cryptomatte_hash(name)[1]      # noqa: E731
        keys = sorted(self.entries, key=self.entries.get)
        names = dict(materials.names)
        if materials._default is not None:
            names[materials._default] = DEFAULT_SURFACE
        material_ids = [0.0] * self.scene.num_materials
        for idx, name in names.items():
            if idx < len(material_ids):
                material_ids[idx] = hash_id(name)
        vl = self.view_layer
        self.scene.set_cryptomatte(
            "CryptoObject" in self.layers, "CryptoMaterial" in self.layers,
            "CryptoAsset" in self.layers, int(vl.pass_cryptomatte_depth),
            [hash_id(o) for o, _ in keys], [hash_id(a) for _, a in keys], material_ids)
        listed = {"CryptoObject": {o for o, _ in keys}, "CryptoAsset": {a for _, a in keys},
                  "CryptoMaterial": set(names.values())}
        fields = {}
        for layer in self.layers:
            fields.update(metadata(vl.name, layer, sorted(listed[layer]), self.tc))
        return fields
