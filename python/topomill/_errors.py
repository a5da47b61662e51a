"""The exceptions topomill raises: the command line's exit-2 errors, with where they are."""


class InputError(ValueError):
    """Bad input: a height-map file, an argument, a value out of range.

    ``str(e)`` is the message the command line prints; ``file``, ``line`` and ``column`` say
    where (0 where there is no line), ``key`` names the key or argument at fault and
    ``message`` is what was expected, without the place.
    """

    def __init__(self, text, file="", line=0, column=0, key="", message=""):
        super().__init__(text)
        self.file = file
        self.line = line
        self.column = column
        self.key = key
        self.message = message or text


class SceneError(InputError):
    """A scene that cannot run: malformed TOML, an unknown key, a value its schema refuses, a
    combination a model cannot represent. ``file`` is the scene's file (or the ``set()`` that
    wrote the value: ``--set key=value``, as on the command line)."""


class PluginError(RuntimeError):
    """A plugin library that cannot be used (no entry point, another ABI, a duplicate name)."""
