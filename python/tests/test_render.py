"""Renders from Python against the CLI's, bit for bit; loaded scenes,
outputs, parameters and the GIL."""

import os
import re
import threading

import numpy as np
import pytest

import lumis
from conftest import read_pfm, run_cli


def test_default_scene_equals_the_cli_bit_for_bit(cli, tmp_path):
    # The built-in default scene with `photon` (its integrator), small.
    run_cli(cli, "render", "--resolution", "40x32", "--spp", "4", "-q",
            "-o", "cli.pfm", cwd=tmp_path)
    img = lumis.render(resolution=(40, 32), spp=4, progress=False)
    ref = read_pfm(tmp_path / "cli.pfm")
    assert img.shape == (32, 40, 3) and img.dtype == np.float32
    assert np.array_equal(img, ref)
    assert img.metadata["lumis:spp"] == "4"
    assert img.metadata["lumis:integrator"] == "photon"
    assert img.stats["spp"] == 4 and not img.stats["interrupted"]
    assert img.stats["photons"]["iterations"] == 4


def test_a_scene_file_with_integrator_parameters_equals_the_cli(cli, scenes, tmp_path):
    scene = scenes / "test" / "caustic_sphere_glossy.pbrt"
    run_cli(cli, "render", scene, "--resolution", "36x24", "--spp", "2", "--seed", "3",
            "--integrator", "photon", "--photons", "20000", "--caustic-photons", "30000",
            "--caustics", "photons", "--maxdepth", "6", "--crop", "0.25,0.75,0,1",
            "--threads", "1", "-q", "-o", "cli.pfm", cwd=tmp_path)
    img = lumis.render(scene, resolution=(36, 24), spp=2, seed=3, integrator="photon",
                       photons=20000, caustic_photons=30000, caustics="photons",
                       maxdepth=6, crop=(0.25, 0.75, 0, 1), progress=False)
    assert img.shape == (24, 18, 3)
    assert np.array_equal(img, read_pfm(tmp_path / "cli.pfm"))


def test_path_tracing_equals_the_cli_and_scene_file_names_work(cli, scenes, tmp_path):
    scene = scenes / "test" / "caustic_sphere.pbrt"
    run_cli(cli, "render", scene, "--resolution", "24x24", "--spp", "3",
            "--integrator", "path", "--sampler", "independent", "-q", "-o", "cli.pfm",
            cwd=tmp_path)
    ref = read_pfm(tmp_path / "cli.pfm")
    img = lumis.render(str(scene), resolution="24x24", spp=3, integrator="path",
                       sampler="independent", progress=False)
    assert np.array_equal(img, ref)


def test_a_splatting_filter_equals_the_cli(cli, tmp_path):
    # The default scene's Gaussian filter, splatted (as its file says) or sampled.
    run_cli(cli, "render", "--resolution", "24x20", "--spp", "2", "--integrator", "path",
            "--filter-splat", "-q", "-o", "cli.pfm", cwd=tmp_path)
    ref = read_pfm(tmp_path / "cli.pfm")
    img = lumis.render(resolution=(24, 20), spp=2, integrator="path", filter_splat=True,
                       progress=False)
    assert np.array_equal(img, ref)
    sampled = lumis.render(resolution=(24, 20), spp=2, integrator="path", filter_splat=False,
                           progress=False)
    assert not np.array_equal(img, sampled)


def test_a_loaded_scene_renders_again_and_as_a_fresh_load(scenes):
    path = scenes / "test" / "caustic_sphere.pbrt"
    scene = lumis.load(path, integrator="path", resolution=(20, 16), spp=2)
    assert scene.size == (20, 16) and scene.integrator == "path" and scene.spp == 2
    a = lumis.render(scene, seed=1, progress=False)
    b = scene.render(seed=1, progress=False)
    c = lumis.render(scene, seed=2, threads=1, progress=False)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)
    fresh = lumis.render(path, integrator="path", resolution=(20, 16), spp=2, seed=2,
                         progress=False)
    assert np.array_equal(c, fresh)
    assert c.metadata["lumis:seed"] == "2"
    # A parameter that changes the build loads the scene again for itself.
    d = lumis.render(scene, spp=1, seed=2, progress=False)
    assert d.stats["spp"] == 1
    assert lumis.render(scene, seed=2, progress=False).stats["spp"] == 2


def test_a_loaded_photon_scene_renders_again_as_a_fresh_load():
    scene = lumis.load(resolution=(24, 20), spp=2, photons=5000, caustic_photons=5000)
    a = lumis.render(scene, seed=4, progress=False)
    b = lumis.render(scene, seed=4, progress=False)
    fresh = lumis.render(resolution=(24, 20), spp=2, photons=5000, caustic_photons=5000,
                         seed=4, progress=False)
    assert np.array_equal(a, b) and np.array_equal(a, fresh)
    assert a.stats["photons"]["iteration_photons"] == 5000


def test_a_time_budget_stops_the_render(scenes):
    img = lumis.render(scenes / "test" / "caustic_sphere.pbrt", integrator="path",
                       resolution=(16, 16), time=0.3, progress=False)
    assert img.stats["spp"] >= 1
    assert np.isfinite(img).all()


def test_nothing_is_written_unless_asked(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    img = lumis.render(integrator="path", resolution=(8, 8), spp=1, progress=False)
    assert list(tmp_path.iterdir()) == [] and img.stats["written"] == []
    out = lumis.render(integrator="path", resolution=(8, 8), spp=1, progress=False,
                       output=["a.exr", tmp_path / "b.pfm"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.exr", "b.pfm"]
    assert [os.path.basename(p) for p in out.stats["written"]] == ["a.exr", "b.pfm"]
    back = lumis.read(tmp_path / "a.exr")
    assert np.array_equal(back, out)
    assert back.metadata["lumis:spp"] == "1"


def test_unknown_parameters_are_refused_with_a_suggestion():
    with pytest.raises(TypeError, match="did you mean `caustic_photons`"):
        lumis.render(caustic_photon=10)
    with pytest.raises(TypeError, match="unknown parameter `colour`"):
        lumis.load(colour="red")


def test_scene_file_names_of_parameters_are_accepted():
    a = lumis.Job(causticphotons=5)
    b = lumis.Job(caustic_photons=5)
    assert a == b


# The render flags that are keywords of the job rather than integrator
# parameters, and those that only make sense on a command line.
JOB_KEYWORDS = {"spp", "time", "threads", "seed", "integrator", "maxdepth", "resolution",
                "crop", "exposure", "sampler", "filter_splat", "clamp", "accel", "output"}
# `--passes A..B --partial FILE` is `lumis.render_part(scene, A, B)`,
# which returns the part's bytes.
CLI_ONLY = {"help", "quiet", "verbose", "stats", "checkpoint", "checkpoint_every",
            "resume", "display_server", "passes", "partial"}


def test_the_keywords_are_the_clis_flags(cli):
    help_text = run_cli(cli, "render", "--help").stdout
    params = lumis.parameters()
    assert "caustic_photons" in params and "strategy" in params
    for keyword, p in params.items():
        assert p["flag"] + " " in help_text, p["flag"]
        assert keyword == p["flag"][2:].replace("-", "_")
    # And every flag is a keyword: a new parameter table reaches both.
    listed = re.findall(r"^\s+(?:-\w, )?--([a-z][a-z-]*)", help_text, re.M)
    flags = {f.replace("-", "_") for f in listed}
    assert flags - CLI_ONLY == JOB_KEYWORDS | set(params)
    for k in JOB_KEYWORDS:
        lumis.Job(**{k: None})  # known (None: not given)


def test_the_gil_is_released_while_rendering():
    count = 0
    stop = threading.Event()

    def spin():
        nonlocal count
        while not stop.is_set():
            count += 1

    t = threading.Thread(target=spin)
    t.start()
    try:
        img = lumis.render(integrator="path", resolution=(64, 64), spp=64, threads=1,
                           progress=False)
    finally:
        stop.set()
        t.join()
    assert img.stats["seconds"] > 0.05
    # The other thread ran while this one waited for the render.
    assert count > 10_000


def test_progress_goes_to_a_callback_or_stderr(capsys):
    seen = []
    lumis.render(integrator="path", resolution=(32, 32), spp=16,
                 progress=lambda f, spp, s: seen.append((f, spp, s)))
    assert seen and seen[-1][0] == 1.0 and seen[-1][1] == 16
    assert all(0.0 <= f <= 1.0 for f, _, _ in seen)
    lumis.render(integrator="path", resolution=(8, 8), spp=2)
    assert "progress: 100.0%  2 spp" in capsys.readouterr().err
    lumis.render(integrator="path", resolution=(8, 8), spp=2, progress=False)
    assert capsys.readouterr().err == ""
