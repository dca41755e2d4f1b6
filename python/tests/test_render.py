"""Renders into NumPy arrays: the pixels `prism render` writes, bit for bit, on every backend."""
import re

import numpy as np
import pytest

import prism
from conftest import SHOWCASE, SOURCE_DIR, run_cli

# Small, for the GPU backends' kernel builds: a texture, reflections, a directional light.
MIRROR = SOURCE_DIR / "scenes" / "conformance" / "mirror.json"


def test_render_equals_prism_render_exr_bit_for_bit(engine, backend, tmp_path):
    exr = tmp_path / "cli.exr"
    run_cli("render", MIRROR, "-b", backend, "-o", exr, "--width", 32, "--height", 24, "--spp", 2,
            "--aov", "id,path")
    pixels, channels = prism.read_image(exr)
    assert channels == ["R", "G", "B", "id", "path"]

    renderer = engine.renderer(engine.load_scene(MIRROR), backend)
    frame = renderer.render(width=32, height=24, spp=2, aovs=("id", "path"))

    assert frame.rgb.dtype == np.float32 and frame.rgb.shape == (24, 32, 3)
    assert frame.id.shape == (24, 32) and frame.path.shape == (24, 32)
    assert np.array_equal(frame.rgb, pixels[:, :, 0:3])
    assert np.array_equal(frame.id, pixels[:, :, 3])
    assert np.array_equal(frame.path, pixels[:, :, 4])


def test_first_hit_aovs_equal_the_exr_channels_of_those_names(engine, backend, tmp_path):
    exr = tmp_path / "cli.exr"
    run_cli("render", MIRROR, "-b", backend, "-o", exr, "--width", 32, "--height", 24, "--aov", "depth,normal,albedo")
    pixels, channels = prism.read_image(exr)
    frame = engine.renderer(engine.load_scene(MIRROR), backend).render(width=32, height=24,
                                                                       aovs=("depth", "normal", "albedo"))
    assert frame.id is None and frame.path is None
    assert frame.depth.shape == (24, 32) and frame.normal.shape == frame.albedo.shape == (24, 32, 3)
    channel = {name: pixels[:, :, k] for k, name in enumerate(channels)}
    assert np.array_equal(frame.depth, channel["Z"])
    for k, axis in enumerate("XYZ"):
        assert np.array_equal(frame.normal[:, :, k], channel["N." + axis])
    for k, colour in enumerate("RGB"):
        assert np.array_equal(frame.albedo[:, :, k], channel["albedo." + colour])


def test_render_without_aovs_uses_the_scene_settings(engine):
    scene = engine.load_scene(SHOWCASE)
    scene.set_image(prism.ImageSettings(width=20, height=10, spp=1))
    frame = engine.renderer(scene, "reference").render()
    assert frame.rgb.shape == (10, 20, 3)
    assert frame.id is None and frame.path is None
    assert frame.rgb.flags["C_CONTIGUOUS"] and frame.rgb.flags["OWNDATA"] is False  # the render's own buffer


def test_render_rejects_bad_overrides_and_aovs(engine):
    renderer = engine.renderer(engine.load_scene(SHOWCASE), "reference")
    with pytest.raises(ValueError, match=r"^render\(\)\.width: must be in \[1, 16384\], got 0$"):
        renderer.render(width=0)
    with pytest.raises(ValueError, match=r"aovs: unknown channel 'roughness' \(expected id, path, depth, normal or albedo\)"):
        renderer.render(aovs=("roughness",))


def test_unknown_backend_is_a_value_error(engine):
    scene = engine.load_scene(SHOWCASE)
    with pytest.raises(ValueError, match="no-such-backend"):
        engine.renderer(scene, "no-such-backend")


def test_backends_report_what_prism_list_reports(engine):
    listed = {}
    section = None
    for line in run_cli("list").splitlines():
        if not line.startswith(" "):
            section = line
            continue
        match = re.match(r"  (\S+)\s+.*? (usable|not usable here): (.*) \(", line)
        if section == "backends:" and match:
            listed[match.group(1)] = (match.group(2) == "usable", match.group(3))
    found = {b.name: (b.available, b.reason) for b in engine.backends()}
    assert "reference" in found and found["reference"][0]
    assert found == listed
    assert engine.auto_backend() in [name for name, (available, _) in found.items() if available]
