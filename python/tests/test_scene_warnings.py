"""Scene warnings (a scene that loads but looks wrong) through the warnings
module: one prism.SceneWarning per problem from Engine.load_scene, the text
`prism render` prints after "prism: warning: "; a clean scene gives none."""
import json
import subprocess
import warnings

import pytest

import prism
from conftest import CLI


def lit_scene():
    return {
        "prism": 1,
        "camera": {"position": [0, 1, 6], "look_at": [0, 0.5, 0], "fov_y": 40},
        "image": {"width": 8, "height": 6},
        "materials": {"red": {"color": [0.8, 0.1, 0.1]}},
        "lights": [{"type": "point", "position": [3, 5, 4]}],
        "objects": [{"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "red"}],
    }


def load_recording(engine, source):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        scene = engine.load_scene(source)
    return scene, caught


def test_a_clean_scene_loads_without_warnings(engine):
    scene, caught = load_recording(engine, lit_scene())
    assert scene.object_count == 1
    assert [str(w.message) for w in caught] == []


def test_each_problem_is_one_scene_warning_with_its_json_path(engine):
    scene = lit_scene()
    scene["materials"]["red"]["color"] = [255, 128, 0]
    scene["objects"].append({"type": "sphere", "center": [0, 0.5, 20], "radius": 0.5})  # behind the camera at z=6
    loaded, caught = load_recording(engine, scene)
    assert loaded.object_count == 2  # a warning never stops the load
    assert [w.category for w in caught] == [prism.SceneWarning, prism.SceneWarning]
    assert [str(w.message) for w in caught] == [
        "<dict>: materials.red.color: [255, 128, 0] looks like 0-255 values; colours run from 0 to 1 (divide by 255)",
        "<dict>: objects[1]: entirely behind the camera (it can show only in reflections)",
    ]


def test_the_warning_points_at_the_line_that_loaded_the_scene(engine):
    scene = lit_scene()
    scene["lights"] = []
    _, caught = load_recording(engine, scene)
    assert len(caught) == 1
    assert caught[0].filename == __file__
    assert str(caught[0].message) == (
        "<dict>: lights: the scene has no lights and no ambient, so objects other than mirrors and glass render black"
    )


def test_scene_warning_is_a_user_warning_that_a_filter_can_make_an_error(engine):
    assert issubclass(prism.SceneWarning, UserWarning)
    scene = lit_scene()
    scene["lights"] = []
    with warnings.catch_warnings():
        warnings.simplefilter("error", prism.SceneWarning)
        with pytest.raises(prism.SceneWarning, match=r"^<dict>: lights: the scene has no lights"):
            engine.load_scene(scene)


def test_a_file_gives_the_warnings_the_command_line_prints(engine, tmp_path):
    scene = lit_scene()
    scene["materials"]["red"]["color"] = [0, 0, 128]
    file = tmp_path / "blue.json"
    file.write_text(json.dumps(scene))
    _, caught = load_recording(engine, file)
    expected = f"{file}: materials.red.color: [0, 0, 128] looks like 0-255 values; colours run from 0 to 1 (divide by 255)"
    assert [str(w.message) for w in caught] == [expected]
    cli = subprocess.run([CLI, "render", str(file), "-b", "reference", "-o", str(tmp_path / "out.png"), "-q"],
                         capture_output=True, text=True, check=True)
    assert cli.stderr == f"prism: warning: {expected}\n"
