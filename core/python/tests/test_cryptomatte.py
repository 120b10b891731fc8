"""Cryptomatte through the module (film/cryptomatte.h): the ids are the Cryptomatte
specification's hashes; the passes hold each surface's coverage as Cycles 3.4 writes it
(through transparency, sorted, none of a held-out object); and a render without it is the same
image bit for bit."""
import numpy as np
import pytest

import torrance_core as tc

# The Cryptomatte specification's reference implementation's tests (Psyop's
# cryptomatte_utilities tests, CryptoHashing): name (UTF-8) -> float id.
REFERENCE_IDS = {
    "hello": 6.0705627102400005616e-17,
    "cube": -4.08461912519e+15,
    "sphere": 2.79018604383e+15,
    "plane": 3.66557617593e-11,
    "\u0440\u0430\u0432\u043d\u0438\u043d\u0430": -1.3192631212399999468e-25,   # Bulgarian "plane"
    "m\u00e4dchen": 6.2361298211599995797e+25,
}


@pytest.mark.parametrize("name", sorted(REFERENCE_IDS))
def test_ids_are_the_specifications(name):
    hash_32, value = tc.cryptomatte_hash(name)
    assert np.float32(value) == np.float32(REFERENCE_IDS[name])
    bits = np.frombuffer(np.float32(value).tobytes(), np.uint32)[0]
    assert bits & 0x807FFFFF == hash_32 & 0x807FFFFF      # the exponent alone may move


def test_ids_are_normal_floats():
    """Cryptomatte keeps a hash's exponent off 0 and 255: never a denormal, 0, Inf or NaN."""
    values = np.float32([tc.cryptomatte_hash(f"Object_{i}")[1] for i in range(2000)])
    assert np.all(np.isfinite(values)) and np.all(np.abs(values) >= np.finfo(np.float32).tiny)


def floor_and_card(card_alpha=1.0, holdout=False, cryptomatte=True, levels=6, samples=64):
    """An orthographic 8 x 8 view of a floor (object 'Floor', material 'Grey') and a card over
    its left half (object 'Card', parent 'Rig', material 'Red', of alpha card_alpha). Returns
    the render's passes."""
    scene = tc.Scene()
    grey = scene.add_material(base_color=(0.5, 0.5, 0.5))
    red = scene.add_material(base_color=(1, 0, 0), alpha=card_alpha)
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    floor = np.array([[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]], np.float32)
    card = np.array([[-5, -5, 0.5], [0, -5, 0.5], [0, 5, 0.5], [-5, 5, 0.5]], np.float32)
    floor_mesh = scene.add_mesh(floor, tri, material_indices=[grey] * 2)
    card_mesh = scene.add_mesh(card, tri, material_indices=[red] * 2)
    if holdout:
        scene.set_mesh_holdout(card_mesh)
    if cryptomatte:
        ids = lambda *names: [tc.cryptomatte_hash(n)[1] for n in names]  # noqa: E731
        scene.set_cryptomatte(True, True, True, levels, ids("Floor", "Card"), ids("Floor", "Rig"),
                              ids("Grey", "Red"))
        scene.set_mesh_cryptomatte(floor_mesh, 0)
        scene.set_mesh_cryptomatte(card_mesh, 1)
    scene.add_sun(direction=(0, 0, -1), strength=3.0, angle=0.0)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, type="ORTHO", ortho_scale=2.0)
    settings = tc.RenderSettings(width=8, height=8, samples=samples, max_bounces=2, seed=3)
    result = tc.render(scene, settings)
    return np.asarray(result.image), {k: np.asarray(v) for k, v in result.passes.items()}


def coverage(passes, layer, name):
    """Per pixel the coverage of `name`'s id summed over the layer's ranks."""
    wanted = np.float32(tc.cryptomatte_hash(name)[1])
    total = 0.0
    for key in sorted(k for k in passes if k.startswith(f"cryptomatte:{layer}")):
        p = passes[key]
        total = total + np.where(p[..., 0] == wanted, p[..., 1], 0) \
            + np.where(p[..., 2] == wanted, p[..., 3], 0)
    return total


def test_passes_are_named_and_leveled_as_cycles():
    _, passes = floor_and_card(levels=3, samples=4)
    names = sorted(k for k in passes if k.startswith("cryptomatte:"))
    assert names == [f"cryptomatte:Crypto{layer}{i:02d}"
                     for layer in ("Asset", "Material", "Object") for i in range(2)]


def test_opaque_card_covers_its_half():
    _, passes = floor_and_card()
    card = coverage(passes, "CryptoObject", "Card")
    floor = coverage(passes, "CryptoObject", "Floor")
    np.testing.assert_allclose(card + floor, 1.0, atol=1e-5)
    assert card[:, :3].min() > 0.99 and card[:, 5:].max() < 0.01  # left half: the card
    # The edge between columns 3 and 4, filtered as the image: shares symmetric about it.
    assert 0.05 < card[:, 4].min() and card[:, 3].max() < 0.95
    np.testing.assert_allclose(card[:, 3] + card[:, 4], 1.0, atol=0.01)
    np.testing.assert_allclose(coverage(passes, "CryptoAsset", "Rig"), card, atol=1e-6)
    np.testing.assert_allclose(coverage(passes, "CryptoMaterial", "Grey"), floor, atol=1e-6)


def test_transparent_card_shares_the_pixel_and_ranks_sort():
    """A card of alpha 0.3: 0.3 of its pixels its own, 0.7 the floor's seen through it (as
    sampled: the rays that pass); rank 0 holds the larger (the floor)."""
    _, passes = floor_and_card(card_alpha=0.3)
    card = coverage(passes, "CryptoObject", "Card")[:, :3]
    np.testing.assert_allclose(card, 0.3, atol=1e-5)
    rank0 = passes["cryptomatte:CryptoObject00"][:, :3]
    assert np.all(rank0[..., 0] == np.float32(tc.cryptomatte_hash("Floor")[1]))
    np.testing.assert_allclose(rank0[..., 1], 0.7, atol=0.06)
    np.testing.assert_allclose(rank0[..., 1].mean(), 0.7, atol=0.01)


def test_a_held_out_object_has_no_id():
    _, passes = floor_and_card(holdout=True)
    assert coverage(passes, "CryptoObject", "Card").max() == 0.0


def test_a_render_without_it_is_the_same_image():
    with_it, _ = floor_and_card(card_alpha=0.6)
    without, passes = floor_and_card(card_alpha=0.6, cryptomatte=False)
    assert not any(k.startswith("cryptomatte:") for k in passes)
    assert np.array_equal(with_it, without)


def test_ids_past_the_slots_go_into_the_last_one():
    """Two levels (2 slots) and three surfaces in every pixel (two cards of alpha 0.5 over the
    floor): the floor, found with both slots taken, adds into the last one (Cycles'
    film_write_cryptomatte_slots), so the ranks still sum to 1."""
    scene = tc.Scene()
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    quad = lambda z: np.array([[-5, -5, z], [5, -5, z], [5, 5, z], [-5, 5, z]], np.float32)  # noqa: E731
    materials = [scene.add_material(base_color=(0.5, 0.5, 0.5), alpha=a) for a in (1.0, 0.5, 0.5)]
    for entry, (z, material) in enumerate(zip((0.0, 0.5, 1.0), materials, strict=True)):
        scene.set_mesh_cryptomatte(scene.add_mesh(quad(z), tri, material_indices=[material] * 2),
                                   entry)
    ids = [tc.cryptomatte_hash(n)[1] for n in ("Floor", "Low", "High")]
    scene.set_cryptomatte(True, False, False, 2, ids, ids, [0.0] * 3)
    scene.add_sun(direction=(0, 0, -1), strength=1.0, angle=0.0)
    matrix = np.eye(4)
    matrix[2, 3] = 5.0
    scene.set_camera(matrix, type="ORTHO", ortho_scale=2.0)
    result = tc.render(scene, tc.RenderSettings(width=4, height=4, samples=64, max_bounces=0))
    p = np.asarray(result.passes["cryptomatte:CryptoObject00"])
    assert sorted(k for k in result.passes if k.startswith("cryptomatte:")) == \
        ["cryptomatte:CryptoObject00"]
    # The high card's 0.5 (every sample meets it first) in the first slot it took; the low
    # card's slot takes the floor's share too (0.25 + 0.25 as sampled); the floor has none.
    passes = {"cryptomatte:CryptoObject00": p}
    assert np.all(np.sort(p[..., [0, 2]], axis=-1) == np.sort(np.float32(ids[1:])))
    np.testing.assert_allclose(coverage(passes, "CryptoObject", "High"), 0.5, atol=1e-5)
    assert abs(float(coverage(passes, "CryptoObject", "Low").mean()) - 0.5) < 0.03
