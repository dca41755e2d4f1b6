"""prism.compare: the conformance metrics of `prism conform`, on arrays."""
import math

import numpy as np
import pytest

import prism
from conftest import SHOWCASE


def test_compare_counts_stable_and_edge_pixels_over_the_threshold():
    # The case of tests/conformance/conform_run_test.cpp (ConformMeasure), through Python:
    # 4 x 3, the left two columns path 1, the right two path 2: columns 0 and 3 are stable.
    reference = np.full((3, 4, 3), 0.5, dtype=np.float32)
    path = np.array([[1, 1, 2, 2]] * 3, dtype=np.float32)
    image = reference.copy()
    image[0, 0, 1] += 0.017  # stable, over
    image[0, 1, 2] -= 0.015  # edge, under
    image[1, 2, 0] = math.nan  # edge, NaN
    m = prism.compare(reference, image, path=path)
    assert (m.pixels, m.pixels_over, m.nonfinite) == (12, 2, 1)
    assert (m.stable_pixels, m.stable_over) == (6, 1)
    assert (m.edge_pixels, m.edge_over) == (6, 1)


def test_without_a_path_every_pixel_is_an_edge():
    reference = np.zeros((2, 2, 3), dtype=np.float32)
    image = reference.copy()
    image[1, 1] = [0.0, 0.5, 0.0]
    m = prism.compare(reference, image)
    assert (m.stable_pixels, m.edge_pixels, m.edge_over) == (0, 4, 1)
    assert m.max_error == 0.5
    assert m.rms_error == pytest.approx(math.sqrt(0.25 / 12))  # OpenImageIO: over every channel of every pixel


def test_compare_refuses_mismatched_shapes():
    with pytest.raises(ValueError, match="image: its shape differs"):
        prism.compare(np.zeros((2, 2, 3)), np.zeros((2, 3, 3)))
    with pytest.raises(ValueError, match=r"path: expected an array of shape \(height, width\)"):
        prism.compare(np.zeros((2, 2, 3)), np.zeros((2, 2, 3)), path=np.zeros((3, 2)))


def test_a_backend_against_the_reference(engine):
    scene = engine.load_scene(SHOWCASE)
    reference = engine.renderer(scene, "reference").render(width=32, height=24, aovs=("path",))
    other = engine.renderer(scene, "reference").render(width=32, height=24)
    m = prism.compare(reference.rgb, other.rgb, path=reference.path)
    assert (m.rms_error, m.max_error, m.pixels_over) == (0.0, 0.0, 0)
    assert m.stable_pixels + m.edge_pixels == 32 * 24 and m.stable_pixels > 0 and m.edge_pixels > 0
