#!/usr/bin/env python3
"""Every backend against the reference, from Python: a notebook-style script.

Renders a scene on every backend that can run here, prints each one's error
against the reference backend (prism conform's metrics: RMS, max, pixels
over the threshold, split into stable pixels and edges by the reference's
path AOV) and its render time, and saves a side-by-side figure of the images
and their error maps when matplotlib is installed.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/compare_backends.py \
        scenes/showcase.json --width 320 --height 180 --figure out/backends.png
"""
import argparse
import pathlib
import sys
import time

import numpy as np

import prism

HERE = pathlib.Path(__file__).resolve().parent


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default=HERE.parents[1] / "scenes" / "showcase.json")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=180)
    parser.add_argument("--spp", type=int, default=None, help="samples per pixel (default: the scene's)")
    parser.add_argument("--figure", default="backends.png", help="where to save the figure")
    return parser.parse_args()


def timed_render(renderer, **settings):
    """The frame and the time of a second render (the first may compile a GPU kernel)."""
    renderer.render(**settings)
    start = time.perf_counter()
    frame = renderer.render(**settings)
    return frame, (time.perf_counter() - start) * 1000


# %% Render on every backend that can run here.
def render_all(engine, scene, settings):
    frames = {}
    for info in engine.backends():
        if not info.available:
            print(f"{info.name:10s} skipped: {info.reason}")
            continue
        aovs = ("path",) if info.name == "reference" else ()
        frames[info.name] = timed_render(engine.renderer(scene, info.name), aovs=aovs, **settings)
    return frames


# %% Each against the reference.
def report(frames):
    reference, _ = frames["reference"]
    print(f"{'backend':10s} {'time ms':>9s} {'rms':>9s} {'max':>9s} {'over':>8s} {'stable over':>12s} {'edge over':>10s}")
    metrics = {}
    for name, (frame, ms) in frames.items():
        m = prism.compare(reference.rgb, frame.rgb, path=reference.path)
        metrics[name] = m
        print(f"{name:10s} {ms:9.1f} {m.rms_error:9.2e} {m.max_error:9.2e} {m.pixels_over:8d} "
              f"{m.stable_over:5d}/{m.stable_pixels:<6d} {m.edge_over:4d}/{m.edge_pixels:<5d}")
    return metrics


# %% A side-by-side figure: each image, and its error against the reference.
def save_figure(frames, metrics, file):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed (Debian: python3-matplotlib): no figure saved")
        return
    reference = frames["reference"][0].rgb
    fig, axes = plt.subplots(2, len(frames), figsize=(4 * len(frames), 5), squeeze=False)
    for column, (name, (frame, ms)) in enumerate(frames.items()):
        axes[0, column].imshow(np.clip(frame.rgb, 0, 1) ** (1 / 2.2))  # linear to display, roughly
        axes[0, column].set_title(f"{name}: {ms:.0f} ms")
        error = np.abs(frame.rgb - reference).max(axis=2)
        axes[1, column].imshow(error, cmap="inferno", vmin=0, vmax=0.016 * 4)
        axes[1, column].set_title(f"rms {metrics[name].rms_error:.1e}, max {metrics[name].max_error:.1e}")
        for row in (0, 1):
            axes[row, column].axis("off")
    fig.tight_layout()
    fig.savefig(file, dpi=100)
    print(f"saved {file}")


def main():
    args = parse_args()
    engine = prism.Engine()
    scene = engine.load_scene(args.scene)
    settings = {"width": args.width, "height": args.height, "spp": args.spp}
    frames = render_all(engine, scene, settings)
    if "reference" not in frames:
        sys.exit("the reference backend cannot run here")
    save_figure(frames, report(frames), args.figure)


if __name__ == "__main__":
    main()
