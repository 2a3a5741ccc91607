"""Scenes, cameras, objects and lights from Python, by the scene file's names.

Each builder returns what the scene file holds (objects and lights as dicts, with the keys given and nothing
else), so the names, the defaults and the checks are the scene files' own (docs/scene-format.md): a field left
out takes the file's default, a bad one raises sol.InvalidArgumentError naming it ("'objects[0].radius' must be
..."). Points are Sol coordinates (x, y, z), directions frame components, colours linear RGB in [0, 1].

    scene = sol.scene([sol.plane_z(-1, pattern="checker"), sol.ball((1, 0, 0), 0.3, color=(0.9, 0.3, 0.2))],
                      camera=sol.camera(position=(0, 0, 0.5), forward=(1, 0, -0.3)),
                      lights=[sol.point_light((0, 0, 1), intensity=3)])
    closer = scene.replace(camera={"position": (0.5, 0, 0.5)})   # the rest of the camera as it was
"""
import json as _json
import math as _math
import re as _re

from . import _sol

__all__ = ["scene", "camera", "ball", "box", "tube", "union", "intersection", "difference", "plane_x", "plane_y",
           "plane_z", "point_light", "directional_light"]


def _plain(value):
    """JSON's types for what Python hands in: tuples and NumPy arrays as lists, NumPy numbers as floats."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if hasattr(value, "tolist"):  # NumPy arrays and scalars
        return _plain(value.tolist())
    if isinstance(value, _sol.Camera):
        return _camera_fields(value)
    return value


def _camera_fields(c):
    """A camera's fields as the scene file writes them: through a scene holding it."""
    return _json.loads(_sol._scene_with_camera(c).to_json())["camera"]


def _check_finite(value, path, source):
    """JSON has no NaN or infinity: a non-finite number is refused here, naming its field (as the scene file's
    reader names a bad value), rather than written as JSON no reader takes."""
    if isinstance(value, dict):
        for k, v in value.items():
            _check_finite(v, f"{path}.{k}" if path else k, source)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            _check_finite(v, f"{path}[{i}]", source)
    elif isinstance(value, float) and not _math.isfinite(value):
        raise _sol.InvalidArgumentError(f"{source}: {path} must be a finite number, got {value}")


# The scene file reader's "(line L, column C)": a place in JSON that sol.scene and its kin wrote, not the user.
_JSON_PLACE = _re.compile(r" \(line [0-9]+, column [0-9]+\)$")


def _parse(fields, source):
    plain = _plain(fields)
    _check_finite(plain, "", source)
    try:
        return _sol.parse_scene(_json.dumps(plain), source)
    except _sol.InvalidArgumentError as e:
        # The field's name stays (objects[0].radius: the list's index and the builder's keyword).
        raise _sol.InvalidArgumentError(_JSON_PLACE.sub("", str(e))) from None


def scene(objects, *, camera=None, lights=None, **world):
    """A scene from the scene file's fields.

    objects: the objects (sol.ball, sol.box, sol.tube, sol.union/intersection/difference of them, sol.plane_x/y/z,
        or dicts with the file's keys).
    camera: a sol.Camera (sol.camera(...)) or a dict of the file's camera keys; the file's default camera if None.
    lights: the lights (sol.point_light, sol.directional_light, or dicts); the file's default if None.
    world: the other top-level keys: quotient ("none", "golden" or {"monodromy": [[a, b], [c, d]], "fibre_area": S}:
        the torus bundle of A, sol.Lattice(A)), ambient, fog ({"color", "density"}),
        fog_distance, max_distance, max_steps, hit_epsilon, samples, background, ...

    Raises sol.InvalidArgumentError naming the field for anything the scene file would refuse.
    """
    fields = dict(world, objects=list(objects))
    if camera is not None:
        fields["camera"] = camera
    if lights is not None:
        fields["lights"] = list(lights)
    return _parse(fields, "sol.scene")


def camera(**fields):
    """A sol.Camera from the scene file's camera keys: position (Sol coordinates), forward and up (frame
    components) or look_at (a point: forward aims at it in Sol; in a quotient give the scene's camera
    look_at, or use sol.aim with the lattice), fov (vertical, degrees), projection ("perspective", "equirectangular", "fisheye"), fisheye_fov
    (degrees), frustum ([left, right, down, up] tangents), aperture and focus_distance (depth of field: a thin lens's
    radius and the arc length in focus; with look_at and no focus_distance it focuses on the point). Keys left out
    take the file's defaults."""
    # (Through a scene file with an object, which a scene needs.)
    return _parse({"camera": fields, "objects": [{"type": "plane_z"}]}, "sol.camera").camera


def _replace(self, **changes):
    """A copy of this scene with top-level fields changed, by the scene file's names. camera and fog given as
    dicts change only the keys they name; everything else is replaced whole (objects=[...] the objects)."""
    fields = _json.loads(self.to_json())
    for key, value in changes.items():
        value = _plain(value)
        if key in ("camera", "fog") and isinstance(value, dict) and isinstance(fields.get(key), dict):
            kept = dict(fields[key])
            if key == "camera" and "look_at" in value:
                kept.pop("forward", None)  # look_at takes forward's place
            fields[key] = dict(kept, **value)
        else:
            fields[key] = value
    return _parse(fields, "Scene.replace")


def _to_dict(self):
    """The scene as the scene file's JSON, as Python dicts and lists."""
    return _json.loads(self.to_json())


_sol.Scene.replace = _replace
_sol.Scene.to_dict = _to_dict


def _object(kind, fields, extra):
    return dict({"type": kind}, **{k: v for k, v in dict(fields, **extra).items() if v is not None})


def ball(center, radius, **fields):
    """A ball: the points within `radius` of `center` (Sol distance). Other keys: color, pattern ("none",
    "circles", "checker"), exact (true: drawn as the exact geodesic sphere)."""
    return _object("ball", {"center": center, "radius": radius}, fields)


def box(center, half_size, **fields):
    """A box: center * ([-a, a] x [-b, b] x [-c, c]) for half_size (a, b, c). Other keys: color, pattern."""
    return _object("box", {"center": center, "half_size": half_size}, fields)


def tube(axis, through, radius, **fields):
    """A tube of `radius` around the line through `through` along `axis` ("x", "y", "z", "gamma1", "gamma2",
    "gamma3", or a vertical or horizontal direction (a, b, c)). Other keys: color, pattern."""
    return _object("tube", {"axis": axis, "through": through, "radius": radius}, fields)


def union(a, b, **fields):
    """A ∪ B of two solids (sol.ball, sol.box, sol.tube or composites, without appearance keys of their own).
    Other keys: color, pattern, material, emission, mirror (the composite's)."""
    return _object("union", {"a": a, "b": b}, fields)


def intersection(a, b, **fields):
    """A ∩ B of two solids (as sol.union)."""
    return _object("intersection", {"a": a, "b": b}, fields)


def difference(a, b, **fields):
    """A with B taken out of it, A \\ B (as sol.union): the hollow shows B's surface."""
    return _object("difference", {"a": a, "b": b}, fields)


def plane_x(c=0.0, **fields):
    """The plane x = c. Other keys: color, pattern, cutout."""
    return _object("plane_x", {"c": c}, fields)


def plane_y(c=0.0, **fields):
    """The plane y = c. Other keys: color, pattern, cutout."""
    return _object("plane_y", {"c": c}, fields)


def plane_z(c=0.0, **fields):
    """The plane z = c. Other keys: color, pattern, cutout."""
    return _object("plane_z", {"c": c}, fields)


def point_light(position, **fields):
    """A point light at `position`. Other keys: color, intensity, exact (light along the true geodesics), reach,
    falloff ("geodesic", "inverse-square"), shadows."""
    return _object("point", {"position": position}, fields)


def directional_light(direction, **fields):
    """A light from `direction` (frame components, towards the light). Other keys: color, intensity."""
    return _object("directional", {"direction": direction}, fields)
