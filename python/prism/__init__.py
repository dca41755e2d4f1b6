"""Prism, a ray tracer with interchangeable backends, from Python.

    import prism
    engine = prism.Engine()
    scene = engine.load_scene("scenes/showcase.json")        # or a dict in the scene format
    renderer = engine.renderer(scene, backend="auto")
    frame = renderer.render(width=320, height=180, aovs=("path",))
    frame.rgb                                                 # float32 (180, 320, 3), linear RGB
    scene.move_object(scene.object_at(0), (0.5, 1, 0))
    renderer.render().rgb                                     # only the moved object is sent again
    prism.compare(frame.rgb, other.rgb, path=frame.path)      # prism conform's metrics

docs/python.md in the source tree is the guide; help(prism.Renderer.render)
and the other docstrings are the reference.
"""

from ._prism import (
    BackendInfo,
    Camera,
    DirectionalLight,
    Engine,
    Frame,
    Hits,
    ImageSettings,
    Material,
    Metrics,
    PointLight,
    RenderError,
    Renderer,
    Rotation,
    Scene,
    SceneError,
    SceneWarning,
    UpdateCounters,
    compare,
    read_image,
)

__all__ = [
    "BackendInfo",
    "Camera",
    "DirectionalLight",
    "Engine",
    "Frame",
    "Hits",
    "ImageSettings",
    "Material",
    "Metrics",
    "PointLight",
    "RenderError",
    "Renderer",
    "Rotation",
    "Scene",
    "SceneError",
    "SceneWarning",
    "UpdateCounters",
    "compare",
    "read_image",
]
