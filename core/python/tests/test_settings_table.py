"""The add-on's settings table (python_addon/torrance/settings_table.py) against the core's
RenderSettings (core/include/torrance/integrator/render_settings_fields.h, bound with
RenderSettings.FIELDS): every core field is set by a setting of the table or listed, with its
reason, in CORE_ONLY; every setting's field exists; the defaults and the kinds agree where the
table passes the value on."""
import pytest

import torrance_core as tc

PYTHON_TYPE = {'INT': int, 'FLOAT': float, 'BOOL': bool, 'ENUM': str}


@pytest.fixture(scope="module")
def table(load_module):
    return load_module("settings_table")


def test_every_core_field_has_a_place_in_the_table(table):
    core_fields = set(tc.RenderSettings.FIELDS)
    from_table = {s.core for s in table.SETTINGS if s.core is not None}
    listed = from_table | set(table.CORE_ONLY)
    assert not core_fields - listed, (
        f"RenderSettings fields that settings_table.py neither sets (a Setting's core=) nor lists "
        f"in CORE_ONLY: {sorted(core_fields - listed)}")
    assert not listed - core_fields, (
        f"settings_table.py names fields that RenderSettings.FIELDS lacks: "
        f"{sorted(listed - core_fields)}")
    assert not from_table & set(table.CORE_ONLY), "a field both set and CORE_ONLY"


def test_one_setting_per_core_field_and_per_property(table):
    cores = [s.core for s in table.SETTINGS if s.core is not None]
    props = [s.prop for s in table.SETTINGS]
    assert len(cores) == len(set(cores)), f"core fields set twice: {cores}"
    assert len(props) == len(set(props)), f"properties declared twice: {props}"


def test_defaults_and_kinds_agree_with_the_core(table):
    core = tc.RenderSettings()
    for s in table.SETTINGS:
        assert s.kind in table.KINDS, s
        assert isinstance(s.default, PYTHON_TYPE[s.kind]), f"{s.prop}: default {s.default!r}"
        if s.core is None or s.computed:      # computed: core_settings.py, by name
            continue
        value = getattr(core, s.core)
        assert isinstance(value, PYTHON_TYPE[s.kind]), (
            f"scene.torrance.{s.prop} is {s.kind}, RenderSettings.{s.core} is {type(value)}")
        assert value == pytest.approx(s.default, rel=1e-6), (
            f"scene.torrance.{s.prop} defaults to {s.default!r}, "
            f"RenderSettings.{s.core} to {value!r}")


def test_the_fields_round_trip_through_the_constructor():
    defaults = tc.RenderSettings()
    for name in tc.RenderSettings.FIELDS:
        value = getattr(defaults, name)
        again = tc.RenderSettings(**{name: value})
        assert getattr(again, name) == value, name


def test_a_wrong_keyword_is_named():
    with pytest.raises(TypeError, match="'bogus'"):
        tc.RenderSettings(bogus=1)
    with pytest.raises(TypeError, match="samples must be int, got str"):
        tc.RenderSettings(samples="4")
    with pytest.raises(ValueError, match="first_bounce_splits"):
        tc.RenderSettings(first_bounce_splits=17)
