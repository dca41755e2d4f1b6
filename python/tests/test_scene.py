"""Scenes from dicts (the loader's checks and messages, SceneError with the JSON
path) and live edits (the image changes, the renderer's update counters)."""
import json
import math

import numpy as np
import pytest

import prism
from conftest import SHOWCASE, SOURCE_DIR


def small_scene():
    return {
        "prism": 1,
        "camera": {"position": [0, 1.5, 6], "look_at": [0, 0.6, 0], "fov_y": 40},
        "image": {"width": 32, "height": 24},
        "materials": {"red": {"color": [0.8, 0.1, 0.1]}},
        "lights": [{"type": "point", "position": [3, 5, 4]}],
        "objects": [
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},
            {"type": "sphere", "center": [0, 0.7, 0], "radius": 0.7, "material": "red"},
        ],
    }


def test_a_typo_in_a_dict_raises_scene_error_with_the_json_path(engine):
    scene = small_scene()
    scene["objects"][1]["raduis"] = scene["objects"][1].pop("radius")
    with pytest.raises(prism.SceneError) as error:
        engine.load_scene(scene)
    assert error.value.path == "objects[1].raduis"
    assert error.value.source == "<dict>"
    assert str(error.value) == "<dict>: objects[1].raduis: unknown key (did you mean 'radius'?)"
    assert isinstance(error.value, ValueError)


def test_a_dict_gets_the_messages_a_file_gets(engine, tmp_path):
    scene = small_scene()
    scene["materials"]["red"]["ior"] = 0.5
    file = tmp_path / "bad.json"
    file.write_text(json.dumps(scene))
    with pytest.raises(prism.SceneError) as from_file:
        engine.load_scene(file)
    with pytest.raises(prism.SceneError) as from_dict:
        engine.load_scene(scene)
    assert from_file.value.path == from_dict.value.path == "materials.red.ior"
    assert str(from_file.value) == f"{file}: materials.red.ior: must be 0 (opaque) or in [1, 100], got 0.5"
    assert str(from_dict.value) == "<dict>: materials.red.ior: must be 0 (opaque) or in [1, 100], got 0.5"


def test_values_json_cannot_hold_are_refused_with_their_path(engine):
    scene = small_scene()
    scene["objects"][1]["radius"] = math.nan
    with pytest.raises(prism.SceneError, match=r"^<dict>: objects\[1\]\.radius: must be a finite number$"):
        engine.load_scene(scene)
    scene["objects"][1]["radius"] = {0.7}
    with pytest.raises(prism.SceneError) as error:
        engine.load_scene(scene)
    assert error.value.path == "objects[1].radius"


def test_a_dict_renders_as_its_file_does(engine):
    as_dict = json.loads(SHOWCASE.read_text())
    from_dict = engine.load_scene(as_dict, base_dir=SHOWCASE.parent)  # its textures are relative
    from_file = engine.load_scene(SHOWCASE)
    a = engine.renderer(from_dict, "reference").render(width=16, height=12).rgb
    b = engine.renderer(from_file, "reference").render(width=16, height=12).rgb
    assert np.array_equal(a, b)


def test_a_refused_edit_names_the_call_and_changes_nothing(engine):
    scene = engine.load_scene(small_scene())
    before = scene.to_json()
    with pytest.raises(prism.SceneError) as error:
        scene.add_object("sphere", center=(0, 1, 0), radius=-1)
    assert str(error.value) == 'add_object("sphere").radius: must be > 0, got -1'
    assert error.value.path == 'add_object("sphere").radius'
    with pytest.raises(prism.SceneError, match=r"^move_object\(#77\): no object has this id"):
        scene.move_object(77, (0, 0, 0))
    assert scene.to_json() == before


def test_live_edits_change_the_image_and_the_counters(engine, backend):
    scene = engine.load_scene(small_scene())
    renderer = engine.renderer(scene, backend)
    first = renderer.render().rgb
    assert (renderer.counters().prepares, renderer.counters().updates) == (1, 0)

    scene.move_object(scene.object_at(1), (0.6, 0.7, 0))
    moved = renderer.render().rgb
    counters = renderer.counters()
    assert (counters.prepares, counters.updates) == (1, 1)
    assert counters.objects_uploaded >= 1
    assert not np.array_equal(moved, first)

    scene.update_light(scene.light_at(0), prism.PointLight(position=(-3, 5, 4), intensity=0.5))
    relit = renderer.render().rgb
    assert (renderer.counters().prepares, renderer.counters().updates) == (1, 2)
    assert not np.array_equal(relit, moved)

    fresh = engine.renderer(scene, backend).render().rgb  # prepared from scratch with the edited scene
    assert np.array_equal(relit, fresh)


def test_a_scene_built_in_code(engine):
    scene = engine.new_scene()
    scene.set_camera(prism.Camera(position=(0, 2, 8), look_at=(0, 1, 0), fov_y=45))
    scene.set_image(prism.ImageSettings(width=16, height=12))
    scene.set_material("red", prism.Material(color=(0.8, 0.1, 0.1), specular=0.4))
    ball = scene.add_object("sphere", material="red", center=(0, 1, 0), radius=1.0)
    scene.add_object("quadric", coefficients=[1, 0, 1, 0, 0, 0, 0, -0.2, 0, -0.3],
                     clip_min=[None, 0.0, None], clip_max=np.array([-9, 1.5, 9]))
    scene.add_light(prism.DirectionalLight(direction=(-1, -1, -1)))
    assert scene.object_count == 2 and scene.object_index(ball) == 0
    frame = engine.renderer(scene, "reference").render(aovs=("id",))
    assert set(np.unique(frame.id)) <= {-1.0, 0.0, 1.0} and 0.0 in frame.id
    scene.remove_object(ball)
    assert scene.object_index(ball) == -1
    assert engine.load_scene(scene.to_dict()).object_count == 1
