"""The add-on's light sets (python_addon/torrance/export/light_linking.py) from stand-ins of
Blender's collections: include and exclude entries, a child collection's state over its objects,
the default set left out once a collection includes something, too many sets reported."""
from types import SimpleNamespace as NS

import pytest

from conftest import ADDON

ALL = (1 << 64) - 1


@pytest.fixture(scope="module")
def linking(load_module):
    return load_module("light_linking", ADDON / "export")


class Reporter:
    def __init__(self):
        self.warnings = []

    def warning(self, text):
        self.warnings.append(text)


def obj(name):
    return NS(name_full=name)


def link(state):
    return NS(light_linking=NS(link_state=state))


def collection(name, objects=(), children=()):
    """objects: (object, state); children: (collection, state)."""
    return NS(name_full=name, objects=[o for o, _ in objects],
              collection_objects=[link(s) for _, s in objects],
              children=[c for c, _ in children], collection_children=[link(s) for _, s in children],
              all_objects=[o for o, _ in objects] + [o for c, _ in children for o in c.all_objects])


def lit(builder, coll, name):
    """Whether an emitter with receiver collection `coll` lights object `name`."""
    return bool(builder.mask(coll) >> builder.object_set.get(name, 0) & 1)


def test_exclude_leaves_the_rest_lit_include_only_the_included(linking):
    a, b = obj("A"), obj("B")
    excluding = collection("Ex", [(a, 'EXCLUDE')])
    including = collection("In", [(b, 'INCLUDE')])
    sets = linking.SetBuilder([excluding, including], Reporter(), "receiver")
    assert not lit(sets, excluding, "A") and lit(sets, excluding, "B") and lit(sets, excluding, "C")
    assert lit(sets, including, "B")
    assert not lit(sets, including, "A") and not lit(sets, including, "C")
    assert sets.mask(None) == ALL


def test_a_child_collections_state_holds_for_its_objects_and_a_direct_entry_wins(linking):
    a, b = obj("A"), obj("B")
    child = collection("Child", [(a, 'INCLUDE'), (b, 'INCLUDE')])
    parent = collection("Parent", [(b, 'INCLUDE')], children=[(child, 'EXCLUDE')])
    sets = linking.SetBuilder([parent], Reporter(), "receiver")
    assert not lit(sets, parent, "A")  # the child's EXCLUDE, not the object's own INCLUDE
    assert lit(sets, parent, "B")      # the parent's own entry comes after its children's
    assert not lit(sets, parent, "Elsewhere")  # something is included: the default set is not


def test_objects_sharing_their_links_share_a_set(linking):
    a, b, c = obj("A"), obj("B"), obj("C")
    sets = linking.SetBuilder([collection("X", [(a, 'EXCLUDE'), (b, 'EXCLUDE'), (c, 'INCLUDE')])],
                              Reporter(), "blocker")
    assert sets.object_set["A"] == sets.object_set["B"] != sets.object_set["C"]
    assert 0 not in sets.object_set.values()


def test_too_many_sets_are_reported_and_leave_objects_in_the_default_set(linking):
    objects = [obj(f"O{i}") for i in range(70)]
    # Collection i includes objects 0..i: object k's pair is unique (the collections k..69).
    colls = [collection(f"C{i}", [(o, 'INCLUDE') for o in objects[:i + 1]]) for i in range(70)]
    reporter = Reporter()
    sets = linking.SetBuilder(colls, reporter, "receiver")
    assert len(sets.bits) == 64 and len(reporter.warnings) >= 2
    assert max(sets.object_set.values()) == 63
    assert sum(1 for o in objects if o.name_full not in sets.object_set) > 0
