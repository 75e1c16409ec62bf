"""Partial renders (`lumis.render_part`) and their merge (`lumis.merge`):
bit for bit the whole render, whatever the split and the order; parts
from the CLI too; and the refusals."""

import numpy as np
import pytest

import lumis
from conftest import run_cli

SMALL = dict(resolution=(24, 18), progress=False)


def split_render(scene, ranges, **params):
    return [lumis.render_part(scene, a, b, **params) for a, b in ranges]


@pytest.mark.parametrize(
    "params",
    [
        dict(integrator="path"),
        # The default scene's progressive photon mapping: one iteration a pass.
        dict(integrator="photon"),
        # Two passes an iteration: 1..5 and 5..8 start inside one.
        dict(integrator="photon", iteration_spp=2),
    ],
    ids=["path", "photon", "photon-iterationspp-2"],
)
def test_uneven_parts_in_any_order_merge_to_the_whole_render(params):
    whole = lumis.render(spp=8, seed=5, **SMALL, **params)
    parts = split_render(None, [(5, 8), (0, 1), (1, 5)], spp=8, seed=5, **SMALL, **params)
    assert all(isinstance(p, bytes) for p in parts)
    merged = lumis.merge(parts)
    assert merged.shape == whole.shape
    assert np.array_equal(merged, whole)
    assert merged.metadata["lumis:spp"] == "8"
    assert merged.metadata["lumis:parts"] == "3"
    assert merged.stats["spp"] == 8
    # A part alone is not the whole: the test can fail.
    assert not np.array_equal(lumis.merge(split_render(None, [(0, 8)], spp=8, seed=6,
                                                       **SMALL, **params)), whole)


def test_a_part_holds_the_film_sums_packed():
    def size(w, h):
        return len(lumis.render_part(None, 0, 2, spp=4, integrator="path",
                                     resolution=(w, h), progress=False))

    small, large = size(16, 16), size(128, 128)
    # A pixel's count and six 128-bit sums take 104 bytes; a part packs them
    # (docs/distributed.md) to well under half, plus a header (the job, the
    # state) that does not grow with the image.
    grown = large - small
    assert 0 < grown < 104 * (128 * 128 - 16 * 16) / 2
    assert small < 104 * 16 * 16 + 4096


def test_parts_of_a_loaded_scene_and_of_a_job(scenes):
    path = scenes / "test" / "caustic_sphere.pbrt"
    scene = lumis.load(path, integrator="path", resolution=(20, 16), spp=6)
    whole = lumis.render(scene, seed=2, progress=False)
    a = lumis.render_part(scene, 0, 4, seed=2, progress=False)
    job = lumis.Job(path, integrator="path", resolution=(20, 16), spp=6, seed=2)
    b = lumis.render_part(job, 4, 6, progress=False)
    assert job.passes is None  # the caller's job is left as it was
    assert np.array_equal(lumis.merge([bytearray(b), a]), whole)


def test_parts_from_the_cli_merge_in_python(cli, scenes, tmp_path):
    scene = scenes / "test" / "caustic_sphere.pbrt"
    flags = ["--resolution", "20x16", "--spp", "8", "--integrator", "path", "-q"]
    for r, name in [("0..3", "a.lpart"), ("3..8", "b.lpart")]:
        run_cli(cli, "render", scene, *flags, "--passes", r, "--partial", name, cwd=tmp_path)
    whole = lumis.render(scene, resolution=(20, 16), spp=8, integrator="path",
                         progress=False)
    out = tmp_path / "merged.pfm"
    merged = lumis.merge([tmp_path / "b.lpart", str(tmp_path / "a.lpart")], output=out)
    assert np.array_equal(merged, whole)
    assert merged.stats["written"] == [str(out)]
    assert np.array_equal(lumis.read(out), whole)
    # A CLI part and a Python part of the same render merge too.
    b = lumis.render_part(scene, 3, 8, resolution=(20, 16), spp=8, integrator="path",
                          progress=False)
    assert np.array_equal(lumis.merge([tmp_path / "a.lpart", b]), whole)


def parts(ranges, seed=0):
    return split_render(None, ranges, spp=8, seed=seed, integrator="path", **SMALL)


def test_a_gap_is_refused():
    with pytest.raises(RuntimeError, match=r"passes 3\.\.5 are missing"):
        lumis.merge(parts([(0, 3), (5, 8)]))
    with pytest.raises(RuntimeError, match=r"passes 5\.\.8 are missing"):
        lumis.merge(parts([(0, 5)]))


def test_an_overlap_is_refused():
    with pytest.raises(RuntimeError, match="overlaps"):
        lumis.merge(parts([(0, 5), (3, 8)]))


def test_parts_of_different_seeds_are_refused():
    a = parts([(0, 4)], seed=1)[0]
    b = parts([(4, 8)], seed=2)[0]
    with pytest.raises(RuntimeError, match="different renders"):
        lumis.merge([a, b])


def test_bad_parts_and_ranges_are_refused(tmp_path):
    with pytest.raises(RuntimeError, match="nothing to merge"):
        lumis.merge([])
    with pytest.raises(TypeError):
        lumis.merge(b"not a list")
    with pytest.raises(RuntimeError):
        lumis.merge([b"not a part"])
    with pytest.raises(RuntimeError, match=r"not inside this render's passes 0\.\.8"):
        lumis.render_part(None, 4, 9, spp=8, **SMALL)
    with pytest.raises(ValueError, match="empty"):
        lumis.render_part(None, 3, 3, spp=8, **SMALL)
    with pytest.raises(RuntimeError, match="time budget"):
        lumis.render_part(None, 0, 2, time=1.0, **SMALL)


def test_job_passes_is_a_range_or_none():
    job = lumis.Job(spp=8)
    assert job.passes is None
    job.passes = (2, 6)
    assert job.passes == (2, 6)
    assert lumis.Job.from_json(job.to_json()).passes == (2, 6)
    with pytest.raises(ValueError, match="empty"):
        job.passes = (6, 2)
    assert job.passes == (2, 6)
    job.passes = None
    assert job.passes is None


def test_a_merger_takes_parts_one_at_a_time(tmp_path):
    whole = lumis.render(spp=6, integrator="path", **SMALL)
    a, b, c = parts_of = split_render(None, [(2, 3), (0, 2), (3, 6)], spp=6,
                                      integrator="path", **SMALL)
    m = lumis.Merger()
    assert len(m) == 0
    m.add(a)
    m.add(memoryview(b))
    (tmp_path / "c.lpart").write_bytes(c)
    m.add(tmp_path / "c.lpart")
    assert len(m) == 3
    assert np.array_equal(m.finish(), whole)
    with pytest.raises(RuntimeError, match="finished"):
        m.add(a)
    # A part of another render is refused when it is added, with its name.
    m = lumis.Merger()
    m.add(parts_of[0], name="first")
    other = lumis.render_part(None, 0, 2, spp=6, seed=9, integrator="path", **SMALL)
    with pytest.raises(RuntimeError, match="first and second are parts of different"):
        m.add(other, name="second")
    with pytest.raises(RuntimeError, match="nothing to merge"):
        lumis.Merger().finish()


def test_parts_merged_into_a_part_merge_like_any_part():
    whole = lumis.render(spp=6, integrator="path", **SMALL)
    a, b, c = split_render(None, [(0, 1), (1, 4), (4, 6)], spp=6, integrator="path", **SMALL)
    m = lumis.Merger()
    m.add(b)
    m.add(a)
    left = m.finish_part()
    assert isinstance(left, bytes)
    assert np.array_equal(lumis.merge([c, left]), whole)
    # Not a range: a gap between them.
    m = lumis.Merger()
    m.add(a)
    m.add(c)
    with pytest.raises(RuntimeError, match=r"passes 1\.\.4 are missing"):
        m.finish_part()
