"""A study run's `lumis render` flags become the job the CLI makes of
them (lumis_render::session::job_from_flags, used by
lumis.distributed.study's tasks): the
same image bit for bit, for flags of every kind."""

import numpy as np
import pytest

import lumis
from conftest import read_pfm, run_cli

FLAGS = [
    ["--integrator", "path", "--maxdepth", "3", "--sampler", "independent"],
    ["--integrator", "photon", "--photons", "20000", "--caustic-photons", "30000",
     "--caustics", "mis", "--crop", "0.25,0.75,0,1", "--clamp", "4"],
    ["--integrator=photon", "--progressive", "false", "--radiance-photons", "--seed", "3"],
    ["--integrator", "bdpt", "--strategy", "2,3", "--maxdepth", "4"],
]


@pytest.mark.parametrize("flags", FLAGS, ids=["path", "photon", "photon-bools", "bdpt"])
def test_run_flags_make_the_clis_job(cli, scenes, tmp_path, flags):
    scene = scenes / "test" / "caustic_sphere_glossy.pbrt"
    common = ["--resolution", "24x16", "--spp", "2", "--threads", "1"]
    run_cli(cli, "render", scene, *common, *flags, "-q", "-o", "cli.pfm", cwd=tmp_path)
    # Output-only flags are ignored.
    job = lumis._lumis.job_from_flags([str(scene), *common, *flags, "-q", "--stats"])
    assert job.spp == 2 and job.threads == 1
    img = lumis.render(job, progress=False)
    assert np.array_equal(img, read_pfm(tmp_path / "cli.pfm"))


def test_unknown_and_incomplete_flags_are_refused():
    with pytest.raises(ValueError, match="unknown flag `--no-such`"):
        lumis._lumis.job_from_flags(["--no-such", "1"])
    with pytest.raises(ValueError, match="`--spp` needs a value"):
        lumis._lumis.job_from_flags(["--spp"])
    with pytest.raises(ValueError, match="--resolution expects WxH"):
        lumis._lumis.job_from_flags(["--resolution", "12"])
