# Type stubs of the prism package (its classes live in the extension module prism._prism).
from os import PathLike
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike[str]]
_Vec3 = Union[Tuple[float, float, float], Sequence[float], npt.NDArray[np.floating[Any]]]
_Vec2 = Union[Tuple[float, float], Sequence[float], npt.NDArray[np.floating[Any]]]
_Array = npt.ArrayLike

class SceneError(ValueError):
    """A scene, or an edit of one, that the scene loader refuses.

    str(error) is the loader's message; `path` is the JSON path of the
    offending value ('objects[0].raduis') or the API call of an edit
    ('add_object("sphere").radius'), '' when none; `source` is the file's
    name, '<dict>' for a dict, '' for an edit."""
    path: str
    source: str

class SceneWarning(UserWarning):
    """A scene that loads but looks wrong, issued by Engine.load_scene through
    warnings.warn: no light and no ambient, colours above 1 that look like
    0-255 values, objects entirely behind the camera (the warnings `prism
    render` prints). str(warning) is "SOURCE: PATH: what"."""

class RenderError(RuntimeError):
    """A failure at run time: a backend that cannot start here, a device lost, a file not written."""

class BackendInfo:
    """A backend found in the plugin path, as `prism list` reports it."""
    @property
    def name(self) -> str: ...
    @property
    def available(self) -> bool: ...
    @property
    def reason(self) -> str:
        """What it runs on when available; why not otherwise."""
    @property
    def version(self) -> str: ...
    @property
    def path(self) -> str: ...

class Rotation:
    """`degrees` about `axis` (right-hand rule), or a quaternion (w, x, y, z)."""
    axis: Tuple[float, float, float]
    degrees: float
    def __init__(self, axis: _Vec3 = (0.0, 1.0, 0.0), degrees: float = 0.0,
                 quaternion: Optional[Sequence[float]] = None) -> None: ...

class Camera:
    """A pinhole camera; fov_y is the vertical field of view in degrees."""
    position: Tuple[float, float, float]
    look_at: Tuple[float, float, float]
    up: Tuple[float, float, float]
    fov_y: float
    def __init__(self, position: _Vec3 = (0.0, 0.0, 5.0), look_at: _Vec3 = (0.0, 0.0, 0.0),
                 up: _Vec3 = (0.0, 1.0, 0.0), fov_y: float = 60.0) -> None: ...

class Material:
    """A material; the defaults are the scene format's. texture: a texture's name."""
    color: Tuple[float, float, float]
    texture: str
    uv_scale: Tuple[float, float]
    uv_offset: Tuple[float, float]
    diffuse: float
    specular: float
    shininess: float
    reflect: float
    ior: float
    absorb: Tuple[float, float, float]
    def __init__(self, color: _Vec3 = (0.8, 0.8, 0.8), texture: str = "", uv_scale: _Vec2 = (1.0, 1.0),
                 uv_offset: _Vec2 = (0.0, 0.0), diffuse: float = 1.0, specular: float = 0.0,
                 shininess: float = 32.0, reflect: float = 0.0, ior: float = 0.0,
                 absorb: _Vec3 = (0.0, 0.0, 0.0)) -> None: ...

class PointLight:
    """A point light; radius > 0 makes it a visible sphere."""
    position: Tuple[float, float, float]
    color: Tuple[float, float, float]
    intensity: float
    linear: float
    quadratic: float
    radius: float
    def __init__(self, position: _Vec3 = (0.0, 0.0, 0.0), color: _Vec3 = (1.0, 1.0, 1.0),
                 intensity: float = 1.0, linear: float = 0.0, quadratic: float = 0.0,
                 radius: float = 0.0) -> None: ...

class DirectionalLight:
    """A light from a direction (any non-zero length)."""
    direction: Tuple[float, float, float]
    color: Tuple[float, float, float]
    intensity: float
    def __init__(self, direction: _Vec3 = (0.0, -1.0, 0.0), color: _Vec3 = (1.0, 1.0, 1.0),
                 intensity: float = 1.0) -> None: ...

class ImageSettings:
    """The image a scene asks for: size, samples per pixel, depth."""
    width: int
    height: int
    spp: int
    max_depth: int
    def __init__(self, width: int = 640, height: int = 360, spp: int = 1, max_depth: int = 5) -> None: ...

class Scene:
    """A scene held in memory and edited live (Engine.load_scene, Engine.new_scene).

    A refused edit raises SceneError and leaves the scene as it was. Objects
    and lights have stable integer ids."""
    @property
    def object_count(self) -> int: ...
    @property
    def light_count(self) -> int: ...
    @property
    def image(self) -> ImageSettings: ...
    def set_camera(self, camera: Camera) -> None: ...
    def set_image(self, image: ImageSettings) -> None: ...
    def set_background(self, color: _Vec3) -> None: ...
    def set_ambient(self, color: _Vec3) -> None: ...
    def set_shadow_ambient(self, color: _Vec3) -> None: ...
    def add_texture(self, name: str, file: _Path, srgb: bool = True) -> None: ...
    def set_material(self, name: str, material: Material) -> None:
        """Adds the material, or replaces the one of that name."""
    def add_object(self, type: str, material: str = "", rotation: Optional[Rotation] = None,
                   **fields: Any) -> int:
        """Adds an object of any primitive type, its fields as keyword arguments; returns its id."""
    def update_object(self, id: int, **fields: Any) -> None:
        """Changes some fields of an object (the others keep their values)."""
    def move_object(self, id: int, center: _Vec3) -> None: ...
    def rotate_object(self, id: int, rotation: Optional[Rotation]) -> None: ...
    def set_object_material(self, id: int, material: str) -> None: ...
    def remove_object(self, id: int) -> None: ...
    def add_light(self, light: Union[PointLight, DirectionalLight]) -> int: ...
    def update_light(self, id: int, light: Union[PointLight, DirectionalLight]) -> None: ...
    def remove_light(self, id: int) -> None: ...
    def object_index(self, id: int) -> int:
        """The object's index in the scene (its value in the `id` AOV); -1 once removed."""
    def object_at(self, index: int) -> int:
        """The id of the object at `index`."""
    def light_at(self, index: int) -> int: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> dict[str, Any]: ...
    def save(self, file: _Path) -> None: ...

class Frame:
    """One rendered image: NumPy arrays, row 0 at the top."""
    @property
    def rgb(self) -> npt.NDArray[np.float32]:
        """float32, shape (height, width, 3): linear RGB."""
    @property
    def id(self) -> Optional[npt.NDArray[np.float32]]:
        """float32 (height, width): the object index per pixel (-1 background); None unless asked for."""
    @property
    def path(self) -> Optional[npt.NDArray[np.float32]]:
        """float32 (height, width): each pixel's path signature; None unless asked for."""
    @property
    def depth(self) -> Optional[npt.NDArray[np.float32]]:
        """float32 (height, width): the t of sample 0's first hit (inf on a miss); None unless asked for."""
    @property
    def normal(self) -> Optional[npt.NDArray[np.float32]]:
        """float32 (height, width, 3): the first hit's outward unit normal (0 on a miss); None unless asked for."""
    @property
    def albedo(self) -> Optional[npt.NDArray[np.float32]]:
        """float32 (height, width, 3): the first hit's surface colour (0 on a miss); None unless asked for."""

class Hits:
    """The closest hit of each ray, as `prism trace` reports it."""
    @property
    def t(self) -> npt.NDArray[np.float64]:
        """shape (N,): distance along the unit direction; inf on a miss."""
    @property
    def id(self) -> npt.NDArray[np.int32]:
        """shape (N,): the object's index; -1 a miss, -2-k light k's sphere."""
    @property
    def normal(self) -> npt.NDArray[np.float64]:
        """shape (N, 3): the outward unit normal; 0 on a miss."""

class UpdateCounters:
    """What a renderer's backend did since the renderer was made."""
    @property
    def prepares(self) -> int: ...
    @property
    def updates(self) -> int: ...
    @property
    def objects_uploaded(self) -> int: ...
    @property
    def bvh_builds(self) -> int: ...
    @property
    def bvh_refits(self) -> int: ...
    @property
    def kernel_builds(self) -> int: ...

class Renderer:
    """One backend rendering one scene (Engine.renderer).

    Each call sends the backend only what the scene's edits changed. The GIL
    is released while the backend works; Ctrl-C stops it with KeyboardInterrupt."""
    @property
    def backend(self) -> str: ...
    @property
    def scene(self) -> Scene: ...
    def render(self, *, width: Optional[int] = None, height: Optional[int] = None,
               spp: Optional[int] = None, max_depth: Optional[int] = None,
               aovs: Sequence[str] = ()) -> Frame:
        """Renders the scene with its camera; returns a Frame of NumPy arrays.

        width, height, spp, max_depth override the scene's settings for this
        render; aovs: any of "id", "path", "depth", "normal" and "albedo".
        Bit for bit what `prism render` writes to an EXR."""
    def trace(self, origins: _Array, directions: _Array, tmin: Union[float, _Array] = 0.0) -> Hits:
        """The closest hit of each ray (N, 3) with t > tmin, as `prism trace`."""
    def counters(self) -> UpdateCounters: ...
    def stats(self) -> dict[str, Any]: ...

class Engine:
    """The plugin registry: primitive types and backends."""
    def __init__(self, plugin_path: Optional[Sequence[_Path]] = None) -> None: ...
    def backends(self) -> list[BackendInfo]:
        """Every backend found, with whether it can run here and why (`prism list`)."""
    def primitive_types(self) -> list[str]: ...
    def auto_backend(self) -> str: ...
    def load_scene(self, source: Union[_Path, Mapping[str, Any]], base_dir: Optional[_Path] = None) -> Scene:
        """A scene from a file or a dict in the scene format; raises SceneError with the JSON path.

        A scene that loads but looks wrong comes back with one
        warnings.warn(message, SceneWarning) per warning."""
    def new_scene(self) -> Scene:
        """An empty scene: the default camera, 640x360, 1 spp, depth 5."""
    def renderer(self, scene: Scene, backend: str = "auto") -> Renderer: ...

class Metrics:
    """An image against a reference, as `prism conform` measures it."""
    @property
    def mean_error(self) -> float: ...
    @property
    def rms_error(self) -> float: ...
    @property
    def psnr(self) -> float: ...
    @property
    def max_error(self) -> float: ...
    @property
    def pixels(self) -> int: ...
    @property
    def pixels_over(self) -> int: ...
    @property
    def stable_pixels(self) -> int: ...
    @property
    def stable_over(self) -> int: ...
    @property
    def edge_pixels(self) -> int: ...
    @property
    def edge_over(self) -> int: ...
    @property
    def nonfinite(self) -> int: ...

def compare(reference: _Array, image: _Array, path: Optional[_Array] = None,
            threshold: float = 0.016) -> Metrics:
    """`prism conform`'s metrics of image against reference, stable/edge split by the reference's path AOV."""

def read_image(file: _Path) -> Tuple[npt.NDArray[np.float32], list[str]]:
    """An image file's pixels (height, width, channels) and its channel names."""
