# SPDX-License-Identifier: Apache-2.0
"""Light and shadow linking (Blender 4.0+, as Cycles renders it): an emitter's Object > Shading >
Light Linking "Receivers" collection names the objects it lights, its "Blockers" collection those
that cast its shadows, each entry included or excluded (a child collection's state holds for every
object in it). Built here, as Blender's depsgraph builds it, into the core's light sets
(core/include/torrance/lights/light_linking.h):

* every distinct collection used by some emitter gets a bit (at most 64);
* every object those collections reach gets the pair (collections including it, collections
  excluding it); objects sharing a pair share a set, numbered from 1 (0: the default set of every
  object no collection reaches; at most 63 more);
* an emitter lights the sets its collection includes, or, if it includes none, every set, minus
  the sets it excludes.

Blender 3.x has no light linking: nothing is sent to the core, which then renders as before.
"""

ALL_SETS = (1 << 64) - 1
MAX_COLLECTIONS = 64
MAX_SETS = 64


def collection_entries(collection):
    """(link state, object) for every object the collection reaches: its child collections'
    objects with the child's state (children first, in order), then its own objects with theirs;
    a later entry for the same object overrides an earlier one, as in Blender."""
    children = getattr(collection, "collection_children", ())
    for child, link in zip(collection.children, children, strict=False):
        state = link.light_linking.link_state
        for obj in child.all_objects:
            yield state, obj
    for obj, link in zip(collection.objects, getattr(collection, "collection_objects", ()),
                         strict=False):
        yield link.light_linking.link_state, obj


class SetBuilder:
    """One kind of linking (receivers or blockers): each object's set, each collection's mask."""

    def __init__(self, collections, reporter, what):
        self.bits = {}        # collection name -> its bit
        states = {}           # object name -> [include bits, exclude bits]
        for collection in collections:
            if collection.name_full in self.bits:
                continue
            if len(self.bits) >= MAX_COLLECTIONS:
                reporter.warning(f"More than {MAX_COLLECTIONS} light linking {what} collections: "
                                 f"'{collection.name_full}' and later ones link nothing")
                continue
            bit = 1 << len(self.bits)
            self.bits[collection.name_full] = bit
            for state, obj in collection_entries(collection):
                pair = states.setdefault(obj.name_full, [0, 0])
                if state == 'INCLUDE':
                    pair[0] |= bit
                    pair[1] &= ~bit
                else:
                    pair[1] |= bit
                    pair[0] &= ~bit
        set_of_pair = {}
        self.object_set = {}
        included = {bit: 0 for bit in self.bits.values()}
        excluded = dict(included)
        for name, (include, exclude) in states.items():
            key = (include, exclude)
            if key not in set_of_pair:
                if len(set_of_pair) + 1 >= MAX_SETS:
                    reporter.warning(f"More than {MAX_SETS - 1} light linking {what} sets: "
                                     f"'{name}' stays in the default set")
                    continue
                set_of_pair[key] = len(set_of_pair) + 1
            light_set = set_of_pair[key]
            self.object_set[name] = light_set
            for bit in self.bits.values():
                if include & bit:
                    included[bit] |= 1 << light_set
                if exclude & bit:
                    excluded[bit] |= 1 << light_set
        self.mask_of_bit = {bit: (included[bit] or ALL_SETS) & ~excluded[bit] & ALL_SETS
                            for bit in self.bits.values()}

    def mask(self, collection):
        """The sets an emitter with this collection reaches (every set without one)."""
        if collection is None or collection.name_full not in self.bits:
            return ALL_SETS
        return self.mask_of_bit[self.bits[collection.name_full]]


class LightLinking:
    """The scene's light sets given to the core, and each object's (receiver set, blocker set,
    emitter entry)."""

    def __init__(self, tc_scene, depsgraph, reporter):
        self.entries = {}     # (light mask, shadow mask) -> entry (1..)
        self.emitter_entry = {}
        self.receivers = self.blockers = None
        emitters = []
        from ..blender_versions import has_light_linking
        if not has_light_linking():
            return
        for obj in depsgraph.objects:
            linking = getattr(obj.original, "light_linking", None)
            if linking is not None and (linking.receiver_collection or linking.blocker_collection):
                emitters.append((obj.original.name_full, linking))
        if not emitters:
            return
        self.receivers = SetBuilder([ln.receiver_collection for _, ln in emitters
                                     if ln.receiver_collection], reporter, "receiver")
        self.blockers = SetBuilder([ln.blocker_collection for _, ln in emitters
                                    if ln.blocker_collection], reporter, "blocker")
        for name, linking in emitters:
            key = (self.receivers.mask(linking.receiver_collection),
                   self.blockers.mask(linking.blocker_collection))
            if key != (ALL_SETS, ALL_SETS):
                self.emitter_entry[name] = self.entries.setdefault(key, len(self.entries) + 1)
        if self.entries:
            tc_scene.set_light_link_table(list(self.entries))

    def __bool__(self):
        return bool(self.entries)

    def of(self, obj):
        """(receiver set, blocker set, emitter entry) of an object (all 0: unlinked)."""
        if not self.entries:
            return (0, 0, 0)
        name = obj.original.name_full if obj.original is not None else obj.name_full
        return (self.receivers.object_set.get(name, 0), self.blockers.object_set.get(name, 0),
                self.emitter_entry.get(name, 0))
