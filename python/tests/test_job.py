"""lumis.Job: the library's RenderJob, through JSON and pickles."""

import json
import pickle

import numpy as np
import pytest

import lumis


def full_job():
    return lumis.Job("scene.pbrt", spp=4, time=2.5, seed=3, threads=2, clamp=10.0,
                     integrator="photon", caustic_photons=1000, progressive=False,
                     caustics="gather", strategy=(2, 3), resolution=(8, 6),
                     crop="0,0.5,0,1", maxdepth=7, sampler="independent",
                     output=["x.exr", "x.png"], exposure=-1.0)


def test_json_round_trips():
    j = full_job()
    text = j.to_json()
    back = lumis.Job.from_json(text)
    assert back == j and back.to_json() == text
    data = json.loads(text)
    assert data["budget"] == {"spp": 4, "time": 2.5}
    assert data["seed"] == 3 and data["outputs"] == ["x.exr", "x.png"]
    origins = [o["origin"] for o in data["overrides"]]
    assert "caustic_photons=" in origins and "integrator=" in origins
    assert j != lumis.Job("scene.pbrt")


def test_fields_and_pickles():
    j = full_job()
    assert (j.spp, j.time, j.seed, j.threads, j.clamp) == (4, 2.5, 3, 2, 10.0)
    assert str(j.scene) == "scene.pbrt" and j.accel == "bvh"
    j.seed = 9
    assert lumis.Job.from_json(j.to_json()).seed == 9
    assert pickle.loads(pickle.dumps(j)) == j
    k = j.with_params(spp=8)
    assert k.spp == 8 and j.spp == 4
    with pytest.raises(ValueError, match="not a render job"):
        lumis.Job.from_json('{"seed": "x"}')


def test_setting_a_parameter_again_replaces_it():
    j = lumis.Job(photons=10)
    j.set(photons=20)
    assert [o["params"] for o in j.overrides] == ['"integer photons" [ 20 ]']
    j.set(photons=20)
    assert j == lumis.Job(photons=20)


def test_a_job_renders_as_its_parameters_do(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    job = lumis.Job(integrator="path", resolution=(12, 10), spp=2, seed=5)
    a = lumis.render(job, progress=False)
    b = lumis.render(integrator="path", resolution=(12, 10), spp=2, seed=5, progress=False)
    assert np.array_equal(a, b)
    # A job read back from JSON, with its outputs.
    job.set(output="j.pfm")
    c = lumis.render(lumis.Job.from_json(job.to_json()), progress=False)
    assert np.array_equal(lumis.read(tmp_path / "j.pfm"), c)
    # Keywords given with a job override it.
    d = lumis.render(job, seed=6, output=[], progress=False)
    assert d.metadata["lumis:seed"] == "6" and not np.array_equal(d, a)


def test_a_refused_setting_leaves_the_job_as_it_was():
    j = lumis.Job(spp=4, photons=10)
    before = j.to_json()
    with pytest.raises(ValueError):
        j.set(photons=20, spp=0)
    with pytest.raises(ValueError):
        j.spp = 0
    with pytest.raises(ValueError):
        j.time = -1.0
    assert j.to_json() == before
