"""examples/python/compare_backends.py runs, and reports every usable backend."""
import os
import subprocess
import sys

from conftest import SOURCE_DIR, found_backends

EXAMPLE = SOURCE_DIR / "examples" / "python" / "compare_backends.py"


def test_compare_backends_reports_each_usable_backend(tmp_path):
    figure = tmp_path / "backends.png"
    scene = SOURCE_DIR / "scenes" / "conformance" / "light_sphere.json"  # a small kernel for the GPU backends
    done = subprocess.run([sys.executable, str(EXAMPLE), str(scene), "--width", "32", "--height", "24", "--figure", str(figure)],
                          capture_output=True, text=True, env=os.environ)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert ["backend", "time", "ms", "rms", "max", "over", "stable", "over", "edge", "over"] in [l.split() for l in lines]
    reported = {line.split()[0] for line in lines if line and line.split()[0] in found_backends()}
    assert reported == set(found_backends())
    reference = next(line.split() for line in lines if line.startswith("reference ") and "skipped" not in line)
    assert reference[2:5] == ["0.00e+00", "0.00e+00", "0"]  # the reference against itself
    try:
        import matplotlib  # noqa: F401
        assert figure.is_file() and f"saved {figure}" in lines
    except ImportError:
        assert "matplotlib is not installed (Debian: python3-matplotlib): no figure saved" in lines
