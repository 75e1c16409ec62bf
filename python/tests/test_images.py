"""Images through write and read, and compare() against `lumis compare`."""

import pickle

import numpy as np
import pytest

import lumis
from conftest import read_pfm, run_cli


def random_image(seed, h=13, w=17, scale=4.0):
    rng = np.random.default_rng(seed)
    return (rng.random((h, w, 3), dtype=np.float32) * scale).astype(np.float32)


@pytest.mark.parametrize("ext", ["exr", "pfm"])
def test_float_formats_round_trip_exactly(tmp_path, ext):
    a = random_image(1)
    a[0, 0] = [0.0, 1e-30, 65504.5]  # beyond half floats: stored as float32
    a[1, 2] = [-1.5, 3.0e7, 0.1]
    path = tmp_path / f"a.{ext}"
    lumis.write(path, a)
    b = lumis.read(path)
    assert isinstance(b, lumis.Image) and b.dtype == np.float32
    assert b.shape == a.shape
    assert np.array_equal(a, b)
    assert b.stats is None


def test_pfm_files_are_written_as_pfm(tmp_path):
    a = random_image(2)
    lumis.write(tmp_path / "a.pfm", a)
    assert np.array_equal(read_pfm(tmp_path / "a.pfm"), a)


def test_exr_metadata_round_trips(tmp_path):
    img = lumis.Image(random_image(3), {"lumis:spp": "7", "note": "hello"})
    lumis.write(tmp_path / "m.exr", img)
    back = lumis.read(tmp_path / "m.exr")
    assert back.metadata["lumis:spp"] == "7" and back.metadata["note"] == "hello"
    lumis.write(tmp_path / "n.exr", img, metadata={"other": "x"})
    assert lumis.read(tmp_path / "n.exr").metadata == {"other": "x"}


def test_png_is_srgb_and_exposure_scales(tmp_path):
    a = np.full((4, 5, 3), 0.18, dtype=np.float32)
    lumis.write(tmp_path / "a.png", a)
    b = lumis.read(tmp_path / "a.png")
    assert b.shape == (4, 5, 3)
    assert np.allclose(b, 0.18, atol=0.004)
    lumis.write(tmp_path / "b.png", a, exposure=1.0)
    assert np.allclose(lumis.read(tmp_path / "b.png"), 0.36, atol=0.006)


def test_other_arrays_are_converted_or_refused(tmp_path):
    a = random_image(4).astype(np.float64)[:, ::2]  # float64, not contiguous
    lumis.write(tmp_path / "a.pfm", a)
    assert np.array_equal(lumis.read(tmp_path / "a.pfm"), a.astype(np.float32))
    with pytest.raises(ValueError, match=r"\(H, W, 3\)"):
        lumis.write(tmp_path / "b.pfm", np.zeros((4, 4)))
    with pytest.raises(ValueError, match="extension"):
        lumis.write(tmp_path / "b.bmp", a)
    with pytest.raises(OSError):
        lumis.read(tmp_path / "missing.exr")


def test_image_attributes_survive_views_and_pickles():
    img = lumis.Image(random_image(5), {"lumis:spp": "3"}, {"spp": 3})
    view = img[2:5]
    assert view.metadata["lumis:spp"] == "3" and view.stats == {"spp": 3}
    back = pickle.loads(pickle.dumps(img))
    assert isinstance(back, lumis.Image)
    assert np.array_equal(back, img) and back.metadata == img.metadata
    assert back.stats == img.stats
    assert type(np.asarray(img)) is np.ndarray


def cli_metrics(cli, cwd, *args):
    out = run_cli(cli, "compare", *args, cwd=cwd).stdout
    lines = {l.split()[0]: l.split()[1:] for l in out.splitlines() if l.strip()}
    return lines


def printed(m):
    """compare()'s figures printed as `lumis compare` prints them."""
    e = lambda v: float(f"{v:.6e}")
    return {
        "pixels": [str(m["pixels"])],
        "MSE": [e(m["mse"])],
        "RMSE": [e(m["rmse"])],
        "relMSE": [e(m["relmse"])],
        "MAE": [e(m["mae"])],
        "mean": ["test", *(f"{v:.6f}" for v in m["mean_test"]),
                 "reference", *(f"{v:.6f}" for v in m["mean_reference"])],
        "ratio": [f"{v:.4f}" for v in m["ratio"]],
    }


def as_numbers(lines):
    out = dict(lines)
    for k in ["MSE", "RMSE", "relMSE", "MAE"]:
        out[k] = [float(lines[k][0])]
    return out


@pytest.mark.parametrize("flags", [[], ["--mask", "0.1,0.6,0.2,0.9"], ["--lit"]])
def test_compare_gives_the_clis_metrics(cli, tmp_path, flags):
    t = random_image(6, h=20, w=24)
    r = random_image(7, h=20, w=24)
    t[3:9, 4:12] = 0.0  # black pixels, for --lit
    lumis.write(tmp_path / "t.pfm", t)
    lumis.write(tmp_path / "r.exr", r)
    kw = {}
    if "--mask" in flags:
        kw["mask"] = (0.1, 0.6, 0.2, 0.9)
    if "--lit" in flags:
        kw["lit"] = True
    ours = lumis.compare(t, r, **kw)
    from_files = lumis.compare(tmp_path / "t.pfm", str(tmp_path / "r.exr"), **kw)
    assert ours == from_files
    theirs = as_numbers(cli_metrics(cli, tmp_path, "t.pfm", "r.exr", *flags))
    assert printed(ours) == theirs
    if flags:
        assert ours["pixels"] < 20 * 24


def test_compare_writes_the_heatmap_and_refuses_other_sizes(tmp_path):
    t, r = random_image(8), random_image(9)
    m = lumis.compare(t, r, heatmap=tmp_path / "h.png", heatmap_error="abs")
    assert (tmp_path / "h.png").is_file()
    lo, hi = m["heatmap_range"]
    assert 0 < lo < hi
    with pytest.raises(ValueError, match="sizes differ"):
        lumis.compare(t, random_image(9, h=5))
    with pytest.raises(ValueError, match="heatmap_error"):
        lumis.compare(t, r, heatmap=tmp_path / "x.png", heatmap_error="sq")
