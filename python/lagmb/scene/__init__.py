"""Scene files: a whole model and how to run it, in TOML.

The format (tables, keys, kinds of value, units, defaults, limits and error
messages) is documented for users in docs/scene-format.md.

``mb.load_scene(path)`` reads a scene and returns a :class:`Scene` with
``.model`` (an ``mb.Model``), ``.settings`` (the keyword arguments of
``mb.simulate``) and ``.output`` (what ``lagmb run`` writes); ``scene.run()``
simulates it, and ``model, settings = mb.load_scene(path)`` unpacks it where
only the model and its settings are wanted. Anything the file gets wrong
raises :class:`SceneError` naming the file, the line, the table and the key.
``mb.save_scene(model, path, settings=None, output=None)`` writes one that loads back into a model giving
the same results to the last bit.

The modules (docs/design.md, section 7): schema.py, what a scene may contain;
lines.py, the line numbers of its tables and keys; values.py, Python values
as TOML text; reader.py, load_scene and Scene; writer.py, save_scene.
"""

from .reader import Scene, SceneElement, SceneError, load_scene
from .schema import MAX_OUTPUTS, MAX_SCENE_BYTES
from .writer import save_scene, scene_text

__all__ = ["Scene", "SceneError", "load_scene", "save_scene"]

# the public classes belong to lagmb.scene (as tracebacks and pickles name them),
# wherever in the package they are defined
for _cls in (Scene, SceneElement, SceneError):
    _cls.__module__ = __name__
del _cls
