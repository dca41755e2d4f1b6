"""The module from an install prefix, in a fresh interpreter, as a user has it:
`cmake --install build --prefix P` and PYTHONPATH=P/<site folder>, nothing else."""
import os
import re
import subprocess
import sys

from conftest import BUILD_DIR

SCRIPT = """
import sys, prism
assert prism.__file__.startswith(sys.argv[1]), prism.__file__
engine = prism.Engine()
scene = engine.load_scene({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
                           "lights": [{"type": "point", "position": [2, 3, 4]}],
                           "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})
frame = engine.renderer(scene, "reference").render(width=8, height=6, aovs=("id",))
assert frame.rgb.shape == (6, 8, 3) and frame.id[3, 4] == 0
assert "Renders the scene with its camera" in prism.Renderer.render.__doc__
print("ok", [b.name for b in engine.backends() if b.available])
"""


def test_the_installed_module_imports_and_renders_in_a_fresh_interpreter(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", str(BUILD_DIR), "--prefix", str(prefix)], check=True,
                   capture_output=True)
    install_dir = os.environ.get("PRISM_PYTHON_INSTALL_DIR", "")
    assert re.fullmatch(r"lib/python3\.\d+/site-packages", install_dir)  # the README names this folder
    site = prefix / install_dir
    assert (site / "prism" / "__init__.pyi").is_file() and (site / "prism" / "py.typed").is_file()
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PRISM_PLUGIN_PATH", "PYTHON"))}
    env["PYTHONPATH"] = str(site)
    done = subprocess.run([sys.executable, "-c", SCRIPT, str(site)], env=env, cwd=tmp_path,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("ok [") and "'reference'" in done.stdout


def test_the_type_stubs_name_everything_the_module_has():
    import ast
    import pathlib

    import prism

    stub = ast.parse((pathlib.Path(prism.__file__).parent / "__init__.pyi").read_text())
    declared = {}
    for node in stub.body:
        if isinstance(node, ast.ClassDef):
            declared[node.name] = {b.name if isinstance(b, ast.FunctionDef) else b.target.id
                                   for b in node.body if isinstance(b, (ast.FunctionDef, ast.AnnAssign))}
        elif isinstance(node, ast.FunctionDef):
            declared[node.name] = set()
    assert set(prism.__all__) <= set(declared)
    for name in prism.__all__:
        item = getattr(prism, name)
        if isinstance(item, type) and not issubclass(item, BaseException):
            public = {n for n in dir(item) if not n.startswith("_")}
            assert public == {n for n in declared[name] if not n.startswith("_")}, name
