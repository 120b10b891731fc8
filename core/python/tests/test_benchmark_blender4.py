"""The Blender 4.x speed/error benchmark's own logic, without rendering (scripts/benchmark
--blender 4.5; docs/blender_versions.md): which Blender, report and reference directories a
version gets, the Cycles variants it compares, the report's ratio against each variant, and the
denoised comparison (--denoised: its own report, the ratio after denoising beside the undenoised
one)."""
import json
import os
import subprocess
from pathlib import Path

from torrance_tools import blender_versions

REPO = Path(__file__).resolve().parents[3]


def test_directories_and_variants_by_blender_version():
    assert blender_versions.report_dir((3, 4, 1)) == str(REPO / "docs" / "benchmark")
    assert blender_versions.report_dir((4, 5, 15)) == str(REPO / "docs" / "benchmark_blender4.5")
    assert blender_versions.reference_dir((3, 4, 1)) == str(REPO / "references")
    assert blender_versions.reference_dir((4, 2, 23)) == str(REPO / "references" / "blender4.2")
    assert list(blender_versions.cycles_variants((3, 4, 1))) == ["cycles"]
    v4 = blender_versions.cycles_variants((4, 5, 15))
    assert {(s["use_light_tree"], s["use_guiding"]) for s in v4.values()} == {
        (False, False), (True, False), (False, True), (True, True)}
    assert v4["cycles"] == {"use_light_tree": False, "use_guiding": False,
                            "use_surface_guiding": False, "use_volume_guiding": False}


def dry_run(*args):
    env = dict(os.environ, TORRANCE_BENCHMARK_DRY_RUN="1")
    return subprocess.run([REPO / "scripts" / "benchmark", *args], env=env, check=True,
                          capture_output=True, text=True).stdout


def test_option_parsing_selects_blender_and_output_directory():
    out = dry_run("--blender", "4.5", "--max-spp", "2", "sphere_chart")
    assert out.startswith(f"{REPO}/scripts/bpy 4.5 -- ")
    assert f"--out {REPO}/docs/benchmark_blender4.5 --max-spp 2 sphere_chart" in out
    out = dry_run("--max-spp", "2")
    assert out.startswith(f"{REPO}/scripts/blender -- --out {REPO}/docs/benchmark --max-spp 2")
    assert "--out /tmp/x" in dry_run("--blender", "4.2", "--out", "/tmp/x")


def rows(seconds_per_spp, errors):
    return [dict(spp=2 ** i, seconds=seconds_per_spp * 2 ** i, rel_mse=e, rel_mse_corrected=e,
                 rel_mse_trim=e, rel_mse_trim_corrected=e, ssim=1 - e, ratio=1.0,
                 block_mean=0.0, finite=True, seeds=1) for i, e in enumerate(errors)]


def report_text(tmp_path, benchmark_report, name, scene, **settings):
    """The report of a synthetic 4.5 run of one scene, with `settings` on top of the defaults."""
    res = dict(made="now", command="scripts/benchmark --blender 4.5", torrance_commit="x",
               torrance_dirty=False, blender="4.5.15 LTS", machine=dict(
                   cpu="cpu", cores=2, system="linux", load_average=[1.0, 1.0, 1.0]),
               settings=dict(width=128, height=96, seeds=8, first_seed=10, max_spp=16,
                             curve_seconds=30.0, toggle_spp=64, toggle_seeds=0,
                             torrance_model="PRINCIPLED_V2",
                             references="references/blender4.5", **settings),
               levers=[], blender_startup_seconds=1.0, total_seconds=60.0,
               scenes={name: scene})
    (tmp_path / "results.json").write_text(json.dumps(res))
    path, _summary = benchmark_report.write_report(str(tmp_path))
    return Path(path).read_text()


def test_report_gives_a_ratio_against_each_cycles_variant(tmp_path, benchmark_report):
    errors = [0.1 / 2 ** i for i in range(5)]          # relMSE ∝ 1/spp for every engine
    scene = dict(title="t", bounces=8, reference=dict(samples=1024, noise_rel_mse=1e-6,
                                                      blender="4.5.15"),
                 torrance=rows(0.2, errors), cycles=rows(0.1, errors),
                 cycles_guiding=rows(0.4, errors), ablation={})
    variants = {"cycles": {"use_guiding": False}, "cycles_guiding": {"use_guiding": True}}
    ratios = benchmark_report.variant_ratios(scene, list(variants))
    assert abs(ratios["cycles"]["geomean"] - 2.0) < 1e-9
    assert abs(ratios["cycles_guiding"]["geomean"] - 0.5) < 1e-9
    text = report_text(tmp_path, benchmark_report, "sphere_chart", scene,
                       cycles_variants=variants)
    assert "# Speed against error: Torrance vs Cycles 4.5.15" in text
    assert "model PRINCIPLED_V2 (Cycles' Principled v2)" in text
    assert "| scene | T / `cycles` | T / `cycles_guiding` |" in text
    assert "| sphere_chart | 2.00 (2.00–2.00) | 0.50 (0.50–0.50) |" in text
    assert "Not measured in this run (`--toggle-seeds 0`)." in text


def test_denoised_runs_need_a_blender_with_oidn_and_write_their_own_report():
    assert blender_versions.report_dir((4, 5, 15), denoised=True) == str(
        REPO / "docs" / "benchmark_denoised_blender4.5")
    out = dry_run("--denoised", "--blender", "4.5", "suzanne")
    assert f"--out {REPO}/docs/benchmark_denoised_blender4.5 --denoised suzanne" in out
    env = dict(os.environ, TORRANCE_BENCHMARK_DRY_RUN="1")
    refused = subprocess.run([REPO / "scripts" / "benchmark", "--denoised"], env=env,
                             capture_output=True, text=True)
    assert refused.returncode == 2 and "Blender 3.4 has no OIDN" in refused.stderr


def test_report_gives_the_ratio_after_denoising_beside_the_undenoised_one(tmp_path,
                                                                          benchmark_report):
    errors = [0.1 / 2 ** i for i in range(5)]
    denoised = [e / 10 for e in errors]
    scene = dict(title="t", bounces=8, seeds=list(range(10, 18)),
                 reference=dict(samples=1024, noise_rel_mse=1e-9, blender="4.5.15"),
                 torrance=rows(0.2, errors), cycles=rows(0.1, errors),
                 torrance_denoised=rows(0.1, denoised), cycles_denoised=rows(0.4, denoised))
    text = report_text(tmp_path, benchmark_report, "suzanne", scene,
                       cycles_variants={"cycles": {"use_guiding": False}},
                       denoising={"denoising_prefilter": "ACCURATE"})
    assert "## After denoising" in text and "denoising_prefilter=ACCURATE" in text
    # denoised: T/C = 0.1/0.4 (goal met); undenoised: 0.2/0.1, relMSE and 1 - SSIM alike
    assert "| [suzanne](#suzanne) | 0.25 | 0.25–0.25 | yes | 0.25 | 2.00 | 2.00 | 8 |" in text
    assert "## Ablation" not in text and (tmp_path / "suzanne.png").exists()
