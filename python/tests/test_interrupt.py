"""Ctrl-C during a render: KeyboardInterrupt, and the renderer still works."""
import os
import signal
import threading
import time

import numpy as np
import pytest

from conftest import SHOWCASE

MAIN_THREAD = threading.main_thread().ident


def send_sigint(how):
    time.sleep(0.5)  # the render below is well under way by then
    if how == "pthread_kill":
        signal.pthread_kill(MAIN_THREAD, signal.SIGINT)  # to the thread waiting in render()
    else:
        os.kill(os.getpid(), signal.SIGINT)  # to the process: any thread, a worker's perhaps


@pytest.mark.parametrize("how", ["pthread_kill", "kill"])
def test_ctrl_c_cancels_a_render_with_keyboard_interrupt(engine, how):
    scene = engine.load_scene(SHOWCASE)
    renderer = engine.renderer(scene, "reference")
    sender = threading.Thread(target=send_sigint, args=(how,))
    sender.start()
    # Minutes of work on any machine: only a cancel ends it within the test's time limit.
    with pytest.raises(KeyboardInterrupt):
        renderer.render(width=1920, height=1080, spp=256)
    sender.join()

    # Usable afterwards, with no trace of the cancelled render.
    after = renderer.render(width=16, height=12).rgb
    assert np.array_equal(after, engine.renderer(scene, "reference").render(width=16, height=12).rgb)
    assert renderer.counters().prepares == 1

    # Python's own handler is back: SIGINT outside a render raises as usual.
    with pytest.raises(KeyboardInterrupt):
        signal.raise_signal(signal.SIGINT)
        time.sleep(1)


def test_ctrl_c_cancels_a_trace(engine):
    # The reference backend tests every object for every ray, one ray after another:
    # a million rays through 2,000 spheres take many seconds.
    spheres = [{"type": "sphere", "center": [x % 50 - 25, x // 50 - 20, -5], "radius": 0.3} for x in range(2000)]
    scene = engine.load_scene({"prism": 1, "camera": {"position": [0, 0, 10], "look_at": [0, 0, 0]},
                               "objects": spheres})
    renderer = engine.renderer(scene, "reference")
    n = 1_000_000
    origins = np.tile([0.0, 0.0, 10.0], (n, 1))
    directions = np.tile([0.0, 0.0, -1.0], (n, 1))
    sender = threading.Thread(target=send_sigint, args=("pthread_kill",))
    sender.start()
    with pytest.raises(KeyboardInterrupt):
        renderer.trace(origins, directions)
    sender.join()
    assert renderer.trace([[0, 0, 10]], [[0, 0, -1]]).id[0] == 1025  # the sphere at (0, 0, -5)


def test_python_runs_during_a_render_and_cannot_edit_its_scene(engine):
    scene = engine.load_scene(SHOWCASE)
    renderer = engine.renderer(scene, "reference")
    outcome = []

    def render():
        try:
            renderer.render(width=1920, height=1080, spp=256)
            outcome.append("finished")
        except KeyboardInterrupt:
            outcome.append("interrupted")

    worker = threading.Thread(target=render)
    worker.start()
    refused = None
    deadline = time.monotonic() + 60
    while refused is None and time.monotonic() < deadline:  # this loop runs only because the GIL is free
        try:
            scene.set_background((0.1, 0.2, 0.3))  # allowed until the render has started
            time.sleep(0.01)
        except RuntimeError as error:
            refused = str(error)
    signal.pthread_kill(worker.ident, signal.SIGINT)
    worker.join()
    assert refused == "the scene is being rendered on another thread; edit it when the render has returned"
    assert outcome == ["interrupted"]
    scene.set_background((0, 0, 0))  # editable again
