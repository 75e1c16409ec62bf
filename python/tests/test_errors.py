"""Scene errors raise SceneError where the CLI reports them; warnings go
through the warnings module."""

import re
import subprocess

import pytest

import lumis

BAD_SCENE = """Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]
Camera "perspective"
WorldBegin
LightSource "point" "rgb I" [ 1 1 1 ]
Shape "sphere" "float radius" [ "big" ]
"""


def cli_location(cli, *args, cwd):
    p = subprocess.run([str(cli), *map(str, args)], cwd=cwd, capture_output=True, text=True)
    assert p.returncode != 0
    m = re.search(r"^(\S+):(\d+):(\d+): error: (.*)$", p.stderr, re.M)
    assert m, p.stderr
    return m.group(1), int(m.group(2)), int(m.group(3)), m.group(4), p.stderr


def test_a_scene_error_has_the_clis_file_line_and_column(cli, tmp_path):
    path = tmp_path / "bad.pbrt"
    path.write_text(BAD_SCENE)
    file, line, column, message, stderr = cli_location(
        cli, "render", path, "-o", "x.exr", cwd=tmp_path
    )
    with pytest.raises(lumis.SceneError) as info:
        lumis.load(path)
    e = info.value
    assert isinstance(e, ValueError)
    assert (e.file, e.line, e.column) == (file, line, column)
    assert e.line == 5 and e.file.endswith("bad.pbrt")
    assert e.message == message
    # The whole diagnostic, as the CLI prints it (line, caret).
    assert str(e) in stderr
    with pytest.raises(lumis.SceneError):
        lumis.render(path, progress=False)


def test_a_bad_value_is_located_at_its_keyword():
    with pytest.raises(lumis.SceneError) as info:
        lumis.render(integrator="photon", photons="many", resolution=(8, 8), spp=1)
    e = info.value
    assert e.file == "photons=" and e.line == 1 and e.column == 21
    assert "many" in str(e)


def test_errors_without_a_location(tmp_path):
    with pytest.raises(lumis.SceneError, match="unknown integrator `nope`") as info:
        lumis.load(integrator="nope")
    assert info.value.file is None and info.value.line is None
    assert "available:" in info.value.help
    with pytest.raises(lumis.SceneError, match="cannot read scene file") as info:
        lumis.load(tmp_path / "missing.pbrt")
    assert info.value.line is None


def test_bad_budgets_and_settings_are_value_errors():
    with pytest.raises(ValueError, match="time budget"):
        lumis.Job(time=-1)
    with pytest.raises(ValueError, match="at least 1"):
        lumis.render(spp=0)
    with pytest.raises(ValueError, match="crop"):
        lumis.Job(crop=(0.5, 0.2, 0, 1))
    with pytest.raises(ValueError, match="accel"):
        lumis.Job(accel="gpu")


def test_an_output_that_cannot_be_written_is_refused_before_rendering(tmp_path):
    with pytest.raises(RuntimeError, match="does not exist"):
        lumis.render(integrator="path", resolution=(8, 8), spp=1, progress=False,
                     output=tmp_path / "no" / "such" / "x.exr")


def test_scene_warnings_are_python_warnings(tmp_path):
    path = tmp_path / "warn.pbrt"
    path.write_text(BAD_SCENE.replace('[ "big" ]', "[ 1 ]").replace(
        'Camera "perspective"', 'Camera "perspective" "float fav" [ 30 ]'))
    with pytest.warns(lumis.SceneWarning, match="fav"):
        scene = lumis.load(path)
    assert any("fav" in w for w in scene.warnings)
