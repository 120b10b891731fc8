# SPDX-License-Identifier: Apache-2.0
"""Torrance against Cycles within Cycles' own seed-to-seed noise, with deliberate faults
(test_alpha_agreement.py, test_alpha_mix_agreement.py, test_glass_agreement.py; with a
higher-sampled reference: test_mix_shader_agreement.py, test_bump_agreement.py).

Cycles renders the reference (seed 0) and a second image (seed 1),
agreement.cycles_reference_and_noise; their metrics set the bounds (agreement.noise_bounds).
Torrance renders other seeds, whose mean metrics must lie within those bounds. Each fault
patches an attribute (a method of the add-on's reader) and must fail them.
"""

import numpy as np

from torrance_tools import render_settings, testing
from torrance_tools.agreement import (cycles_reference_and_noise, failures, format_metrics,
                                      mean_metrics, metrics, noise_bounds, noise_failures,
                                      noise_limits, print_verdict)


def render_torrance(scene, directory, seed, name, samples, bounces):
    """Torrance (PRINCIPLED) at seed; (image, seconds), the image checked for NaN/Inf."""
    render_settings.setup_torrance(scene, samples, bounces, seed=seed, brdf_model='PRINCIPLED')
    img, seconds = testing.render(scene, directory, name)
    testing.check(np.isfinite(img).all(), f"{name}: NaN/Inf in Torrance's image")
    return img, seconds


def render_with_fault(scene, directory, seed, samples, bounces, owner, attr, make_fault):
    """Torrance's image at seed (render_torrance, named "fault") with owner.attr replaced by
    make_fault(original) for the render, and restored after."""
    original = getattr(owner, attr)
    setattr(owner, attr, make_fault(original))
    try:
        return render_torrance(scene, directory, seed, "fault", samples, bounces)[0]
    finally:
        setattr(owner, attr, original)


def faults_missed(scene, directory, seed, samples, bounces, faults, judge):
    """The labels of the faults ((label, owner, attribute, make_fault), render_with_fault) whose
    image judge(label, image) finds nothing wrong with (it prints its figures and returns what
    the image violates); a label beginning "info:" is reported only, never missed."""
    missed = []
    for label, owner, attr, make_fault in faults:
        img = render_with_fault(scene, directory, seed, samples, bounces, owner, attr, make_fault)
        if not judge(label, img) and not label.startswith("info:"):
            missed.append(label)
    return missed


def measure_seeds(scene, directory, samples, bounces, seeds, measure, prefix=""):
    """measure(image) of Torrance's render at each seed (render_torrance, named
    prefix + "torrance<seed>"), each render's time printed."""
    results = []
    for seed in seeds:
        img, seconds = render_torrance(scene, directory, seed, f"{prefix}torrance{seed}", samples,
                                       bounces)
        print(f"Torrance seed {seed}: {seconds:.1f} s", flush=True)
        results.append(measure(img))
    return results


def seed_noise_verdict(scene, directory, samples, bounces, seeds=(2, 3), tolerance=1.5,
                       ratio_sigmas=3.0, ratio_floor=0.015, prefix="", noise_seeds=(1,)):
    """Torrance (seeds) against Cycles' reference within Cycles' own seed-to-seed noise, printed:
    (reference image, Torrance's mean metrics, Cycles' own metrics, the bounds, what the mean
    violates). prefix: before the Torrance images' names; noise_seeds: Cycles' renders whose
    typical noise against the reference (seed 0) sets the bounds."""
    ref, own = cycles_reference_and_noise(scene, directory, samples, bounces,
                                          seeds=(0, *noise_seeds))
    limits = noise_bounds(own, tolerance, ratio_sigmas, ratio_floor)
    print(f"bounds: ratio {limits['ratio'][0]:.4f}..{limits['ratio'][1]:.4f}, block mean "
          f"{limits['block_mean']:.4f}, p90 {limits['block_p90']:.4f}")
    results = measure_seeds(scene, directory, samples, bounces, seeds,
                            lambda img: metrics(img, ref), prefix)
    for seed, r in zip(seeds, results, strict=True):
        print(f"Torrance seed {seed}             : {format_metrics(r)}")
    m = mean_metrics(results)
    bad = failures(m, limits)
    print_verdict("Torrance mean over seeds    ", m, bad)
    return ref, m, own, limits, bad


def agree_within_seed_noise(scene, directory, samples, bounces, what, faults=(), seeds=(2, 3),
                            tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.015, noise_seeds=(1,)):
    """Raises AssertionError unless Torrance agrees with Cycles and every fault is caught.

    faults: (label, owner, attribute, make_fault) - owner.attribute is replaced by
    make_fault(original) for one Torrance render (seeds[0]) and restored. A label beginning
    "info:" is reported only (a fault these figures are known not to see). noise_seeds: as
    seed_noise_verdict's.
    """
    ref, m, _own, limits, bad = seed_noise_verdict(scene, directory, samples, bounces, seeds,
                                                   tolerance, ratio_sigmas, ratio_floor,
                                                   noise_seeds=noise_seeds)
    testing.check(not bad, f"{what} disagrees with Cycles: " + "; ".join(bad))

    def judge(label, img):
        fm = metrics(img, ref)
        fbad = failures(fm, limits)
        print(f"  fault {label:30s}: {format_metrics(fm)}"
              + (f"  caught: {'; '.join(fbad)}" if fbad else "  NOT CAUGHT"), flush=True)
        return fbad
    missed = faults_missed(scene, directory, seeds[0], samples, bounces, faults, judge)
    testing.check(not missed, "faults the comparison does not see: " + ", ".join(missed))


def agree_on_variants(scene, variants, samples, bounces, after_each=None):
    """Each variant (label, setup(scene), faults) of one scene against Cycles within Cycles' own
    noise (agree_within_seed_noise with the camera tests' tolerances), every fault caught, the
    renders reporting nothing, then after_each(scene) if given. All variants run; an
    AssertionError then names every one that failed."""
    import bpy
    directory = testing.tempdir()
    problems = []
    for label, setup, faults in variants:
        setup(scene)
        bpy.context.view_layer.update()
        print(f"--- {label}", flush=True)
        try:
            agree_within_seed_noise(scene, directory, samples, bounces, label, faults=faults,
                                    tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.015)
            testing.check(not testing.last_messages(),
                          f"unexpected reports: {testing.last_messages()}")
            if after_each is not None:
                after_each(scene)
        except AssertionError as e:
            problems.append(f"{label}: {e}")
    testing.check(not problems, " | ".join(problems))


def agree_on_scene(build, samples, bounces, what, faults=(), silent=True, noise_seeds=(1,)):
    """A fresh scene made by build(scene), Torrance against Cycles within Cycles' own noise
    (agree_within_seed_noise with the shader-graph tests' tolerances), every fault caught;
    silent: the renders report nothing either. Returns the scene."""
    scene = testing.clear_scene()
    build(scene)
    agree_within_seed_noise(scene, testing.tempdir(), samples, bounces, what, faults=faults,
                            tolerance=1.5, ratio_sigmas=3.0, ratio_floor=0.004,
                            noise_seeds=noise_seeds)
    if silent:
        testing.check(not testing.last_messages(),
                      f"unexpected reports: {testing.last_messages()}")
    return scene


def agree_with_reference_noise(scene, directory, samples, ref_samples, bounces, faults=(),
                               patch_args=None):
    """Raises AssertionError unless Torrance (seed 0, `samples`) is within noise_limits of a
    Cycles reference (ref_samples, seed 1) set by a second Cycles render (samples, seed 2), and
    every fault is caught.

    faults: (label, patch): for one render each, every add_material()/add_mixture() argument
    dict the add-on's MaterialTable adds goes through patch_args(args, patch) (default:
    patch(args)) first.
    """
    import torrance.materials as materials
    ref, noise = cycles_reference_and_noise(scene, directory, samples, bounces, ref_samples,
                                            seeds=(1, 2))
    lim = noise_limits(noise)
    print(f"allowed: ratio +-{lim['ratio']:.4f}, block mean {lim['block_mean']:.4f}", flush=True)
    img, seconds = render_torrance(scene, directory, 0, "torrance", samples, bounces)
    m = metrics(img, ref)
    bad = noise_failures(m, lim)
    print_verdict(f"torrance ({seconds:.1f} s)", m, bad)
    missed = []
    original = materials.MaterialTable._add
    for label, patch in faults:
        def faulty(self, args, patch=patch):
            if patch_args:
                patch_args(args, patch)
            else:
                patch(args)
            return original(self, args)
        materials.MaterialTable._add = faulty
        try:
            fimg, _ = render_torrance(scene, directory, 0, "fault", samples, bounces)
        finally:
            materials.MaterialTable._add = original
        fm = metrics(fimg, ref)
        fbad = noise_failures(fm, lim)
        print(f"  fault {label:24s}: {format_metrics(fm)}"
              + (f"  caught: {'; '.join(fbad)}" if fbad else "  NOT CAUGHT"), flush=True)
        if not fbad:
            missed.append(label)
    testing.check(not bad, "Torrance disagrees with Cycles: " + "; ".join(bad))
    testing.check(not missed, "faults the comparison does not see: " + ", ".join(missed))
