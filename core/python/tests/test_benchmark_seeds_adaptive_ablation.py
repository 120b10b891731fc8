"""The speed/error benchmark's logic without rendering (scripts/benchmark, issue 10): the seeds
(never a reference's own), a point's average over its seeds, the ladders and the curve budget,
merging a run of some scenes into an earlier one, and the report's summary with and without
adaptive sampling, its ablation tables and its rays/s table, from a synthetic results.json."""
import json
from pathlib import Path

from torrance_tools import benchmark_points, benchmark_results

REPO = Path(__file__).resolve().parents[3]


def test_seeds_are_disjoint_from_the_references_and_the_same_list_each_time():
    seeds = benchmark_points.benchmark_seeds(8, [1, 2])
    assert seeds == list(range(10, 18))
    assert benchmark_points.benchmark_seeds(8, [1, 2]) == seeds
    # a reference made with other seeds: those are skipped, still 8 distinct seeds
    seeds = benchmark_points.benchmark_seeds(8, [11, 13])
    assert len(set(seeds)) == 8 and not {0, 11, 13} & set(seeds)


def test_a_point_is_the_mean_error_over_its_seeds_and_the_median_time():
    rows = [dict(spp=16, seed=10 + i, seconds=s, rel_mse=e, rel_mse_trim=e / 2, ssim=0.9,
                 ratio=1.0, block_mean=0.0, finite=True)
            for i, (s, e) in enumerate([(1.0, 0.01), (3.0, 0.01), (2.0, 0.01), (9.0, 0.09)])]
    point = benchmark_points.aggregate(rows, floor=0.001)
    assert point["seeds"] == 4 and point["seed_list"] == [10, 11, 12, 13]
    assert abs(point["rel_mse"] - 0.03) < 1e-12          # the firefly seed counts: the mean
    assert abs(point["rel_mse_trim"] - 0.015) < 1e-12
    assert abs(point["rel_mse_corrected"] - 0.029) < 1e-12
    assert point["seconds"] == 2.5


def test_ladders_and_the_curve_budget():
    assert benchmark_points.spp_ladder(64) == [4, 8, 16, 32, 64]
    thresholds = benchmark_points.threshold_ladder()
    assert thresholds[0] == 0.1 and thresholds[-1] >= 0.001
    assert all(1.9 < a / b < 2.1 for a, b in zip(thresholds, thresholds[1:], strict=False))
    budget = benchmark_points.CurveBudget(30.0)
    assert budget.next_fits()
    budget.add(5.0)
    assert budget.next_fits()                 # 5 + 2 x 5 <= 30
    budget.add(10.0)
    assert not budget.next_fits()             # 15 + 2 x 10 > 30
    expensive = benchmark_points.CurveBudget(1.0)
    expensive.add(5.0)
    assert expensive.next_fits()              # two points make a curve, whatever they cost
    expensive.add(5.0)
    assert not expensive.next_fits()
    growing = benchmark_points.CurveBudget(20.0)
    growing.add(1.0)
    growing.add(4.0)
    assert not growing.next_fits()            # 5 + 4 x 4 (its growth, not 2 x 4) > 20


def test_a_run_of_some_scenes_replaces_those_and_keeps_the_others():
    def run(made, names):
        return dict(made=made, settings={"seeds": 8}, total_seconds=1.0,
                    scenes={n: dict(title=f"{n} of {made}", run=dict(made=made, seconds=10.0))
                            for n in names})
    earlier = run("t0", ["water", "glint", "mirror"])
    merged = benchmark_results.merge(earlier, run("t1", ["glint"]),
                                     ["sphere_chart", "water", "glint", "mirror"])
    assert list(merged["scenes"]) == ["water", "glint", "mirror"]
    assert merged["scenes"]["glint"]["title"] == "glint of t1"
    assert merged["scenes"]["water"]["title"] == "water of t0"
    assert merged["total_seconds"] == 30.0 and merged["merged_from_runs"] == ["t0", "t1"]
    assert benchmark_results.merge(None, run("t1", ["glint"]), [])["scenes"].keys() == {"glint"}


def measure_stand_in(scene):
    """Stands in for torrance_tools.ray_throughput.measure (written elsewhere): its keys."""
    return dict(integrator_rays_per_second=6.0e6, embree_rays_per_second=10.0e6,
                fraction=0.6 if scene == "water" else 0.3, rays_per_sample=3.5, note="text")


def points(seconds_per_spp, errors, thresholds=None):
    out = []
    for i, e in enumerate(errors):
        out.append(dict(spp=4 * 2 ** i, seconds=seconds_per_spp * 2 ** i, rel_mse=e,
                        rel_mse_corrected=e, rel_mse_trim=e / 2, rel_mse_trim_corrected=e / 2,
                        ssim=1 - e, ratio=1.0, block_mean=0.0, finite=True, seeds=8))
        if thresholds:
            out[-1].update(spp=1024, threshold=thresholds[i], samples_per_pixel=50.0 * 2 ** i)
    return out


def lever(seconds_on, err_on, seconds_off, err_off):
    def row(t, e):
        return dict(spp=64, seconds=t + 0.1, core_seconds=t, rel_mse=e, rel_mse_trim=e,
                    seeds=4)
    return dict(default=True, other=False, on=row(seconds_on, err_on),
                off=row(seconds_off, err_off))


def scene_data(name):
    errors = [0.1 / 2 ** i for i in range(5)]          # relMSE ∝ 1/spp for every curve
    thresholds = [0.1, 0.05, 0.025, 0.0125, 0.00625]
    return dict(title=name, bounces=8, seeds=list(range(10, 18)),
                reference=dict(samples=16384, noise_rel_mse=1e-6, blender="3.4.1", seeds=[1, 2]),
                torrance=points(0.2, errors), cycles=points(0.1, errors),
                torrance_adaptive=points(0.05, errors, thresholds),
                cycles_adaptive=points(0.2, errors, thresholds),
                ablation={"guiding": lever(1.0, 0.01, 1.0, 0.03),
                          "packet_shadow_rays": lever(1.0, 0.01, 2.0, 0.01)},
                rays=measure_stand_in(name), run=dict(made="t0", commit="abc1234", seconds=100.0))


def test_report_has_adaptive_ratios_ablation_tables_and_rays_per_second(tmp_path,
                                                                         benchmark_report):
    res = dict(made="now", command="scripts/benchmark", torrance_commit="x", torrance_dirty=False,
               blender="3.4.1", machine=dict(cpu="cpu", cores=2, system="linux",
                                             load_average=[1.0, 1.0, 1.0]),
               settings=dict(width=128, height=96, seeds=8, first_seed=10, max_spp=1024,
                             curve_seconds=30.0, spp_ladder=[4, 8, 16, 32, 64],
                             adaptive_thresholds=[0.1, 0.05], toggle_spp=64, toggle_seeds=4,
                             torrance_model="PRINCIPLED", cycles_variants={"cycles": {}},
                             references="references"),
               levers=[dict(field="guiding", default=True, other=False),
                       dict(field="packet_shadow_rays", default=True, other=False)],
               blender_startup_seconds=1.0, total_seconds=200.0,
               scenes={n: scene_data(n) for n in ("water", "glint")})
    (tmp_path / "results.json").write_text(json.dumps(res))
    path, summary = benchmark_report.write_report(str(tmp_path))
    text = Path(path).read_text()
    print(text)
    assert abs(summary["water"]["geomean"] - 2.0) < 1e-9
    # plain T/C 2.00 (trimmed 2.00), adaptive T/C 0.25 (trimmed 0.25), 8 seeds
    assert "| [water](#water) | 2.00 | 2.00–2.00 | 2.00 / — / — | no | 2.00 |" in text
    assert "| 0.25 | 0.25–0.25 | 0.25 | 8 |" in text
    # ablation: the overview and a table per scene; gain = (time x relMSE) ratio
    assert ("| path guiding (`guiding` True → False) | 3.00× | 3.00× | 3.00× |" in text)
    assert "| packet shadow rays (`packet_shadow_rays` True → False) | 2.00× |" in text
    assert "**glint**" in text
    assert ("| path guiding (`guiding` True → False) | 1.000 | 1.000 | 1.00× | 1.000e-02 "
            "| 3.000e-02 | 3.00 | 3.00 | 3.00× |") in text
    # rays/s: every numeric key, the goal from `fraction`
    assert ("| scene | `integrator_rays_per_second` | `embree_rays_per_second` | `fraction` "
            "| `rays_per_sample` | goal ≥ 60 % |") in text
    assert "| water | 6.00 M | 10.00 M | 60.0 % | 3.5 | yes |" in text
    assert "| glint | 6.00 M | 10.00 M | 30.0 % | 3.5 | no |" in text
    # per scene: the adaptive points with their thresholds, plots of every curve
    assert "| 0.05 | 100.0 | 0.100 | 5.000e-02 | 2.500e-02 |" in text
    assert (tmp_path / "water.png").stat().st_size > 0
    assert "Rendered t0 at `abc1234` in 100 s." in text        # which run made a merged scene
