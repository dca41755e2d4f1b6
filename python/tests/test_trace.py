"""Tracing NumPy rays: the hits `prism trace --digits 17` prints, exactly."""
import numpy as np
import pytest

from conftest import SOURCE_DIR, run_cli

SCENE = SOURCE_DIR / "scenes" / "conformance" / "light_sphere.json"


def rays():
    """Hits on the floor, the chrome sphere and a light's sphere, misses, a
    secondary ray with tmin, directions of any length."""
    rng = np.random.default_rng(25)
    origins = np.tile([0.0, 1.5, 6.0], (40, 1))
    targets = rng.uniform([-2.5, -0.5, -1.5], [2.5, 2.5, 1.0], (40, 3))
    directions = (targets - origins) * rng.uniform(0.1, 10.0, (40, 1))
    origins = np.vstack([origins, [[0, 0.7, 3], [0, 5, 0]]])
    directions = np.vstack([directions, [[-1.5, 0.5, -2.5], [0, 1, 0]]])
    tmin = np.zeros(len(origins))
    tmin[5] = 2.0
    return origins, directions, tmin


def read_hits(csv):
    rows = [line.split(",") for line in csv.read_text().splitlines()]
    t = np.array([float(r[0]) for r in rows])
    ids = np.array([int(r[1]) for r in rows], dtype=np.int32)
    normals = np.array([[float(v) for v in r[2:5]] for r in rows])
    return t, ids, normals


def test_trace_equals_prism_trace(engine, backend, tmp_path):
    origins, directions, tmin = rays()
    rays_csv = tmp_path / "rays.csv"
    np.savetxt(rays_csv, np.hstack([origins, directions, tmin[:, None]]), delimiter=",", fmt="%.17g")
    hits_csv = tmp_path / "hits.csv"
    run_cli("trace", SCENE, "-b", backend, "--rays", rays_csv, "-o", hits_csv, "--digits", 17)
    t, ids, normals = read_hits(hits_csv)

    hits = engine.renderer(engine.load_scene(SCENE), backend).trace(origins, directions, tmin)
    assert hits.t.dtype == np.float64 and hits.id.dtype == np.int32 and hits.normal.shape == (42, 3)
    assert np.array_equal(hits.t, t)
    assert np.array_equal(hits.id, ids)
    assert np.array_equal(hits.normal, normals)
    assert {-1, 0, 1}.issubset(set(ids)) and any(ids <= -2)  # misses, floor, sphere, a light's sphere


def test_trace_takes_one_tmin_for_all_rays(engine):
    renderer = engine.renderer(engine.load_scene(SCENE), "reference")
    hits = renderer.trace([[0, 5, 0]], [[0, -2, 0]], 1.0)
    assert hits.id[0] == 0 and hits.t[0] == 5.0 and tuple(hits.normal[0]) == (0.0, 1.0, 0.0)
    assert renderer.trace([[0, 5, 0]], [[0, -1, 0]], 6.0).id[0] == -1


def test_trace_refuses_bad_rays(engine):
    renderer = engine.renderer(engine.load_scene(SCENE), "reference")
    with pytest.raises(ValueError, match=r"^rays\[1\]: the direction is zero$"):
        renderer.trace([[0, 0, 0], [0, 0, 0]], [[0, 0, 1], [0, 0, 0]])
    with pytest.raises(ValueError, match=r"^rays\[0\]: not a finite number$"):
        renderer.trace([[0, np.nan, 0]], [[0, 0, 1]])
    with pytest.raises(ValueError, match=r"directions: expected an array of shape \(N, 3\)"):
        renderer.trace(np.zeros((2, 3)), np.zeros((3, 3)))
