"""Python values as TOML text: a scene given as a dict, and the values ``Scene.set`` takes."""

import json
import math
import numbers


def literal(value, where="value"):
    """The TOML form of a bool, number, string or list of them; TypeError for anything else."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)  # the shortest text that reads back as the same double
    if isinstance(value, str):
        # JSON's escapes are TOML's, but for DEL, which TOML wants escaped too.
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007F")
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(literal(v, where) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_key(k)} = {literal(v, where)}" for k, v in value.items()) + "}"
    if hasattr(value, "tolist"):  # numpy scalars and arrays
        return literal(value.tolist(), where)
    raise TypeError(f"{where}: cannot write a {type(value).__name__} in a scene "
                    "(expected a bool, number, string, list or dict)")


def _key(k):
    if not isinstance(k, str):
        raise TypeError(f"scene keys are strings, got {k!r}")
    bare = k and all(c.isalnum() and c.isascii() or c in "_-" for c in k)
    return k if bare else json.dumps(k, ensure_ascii=False)


def document(scene):
    """A scene dict ({"tool": {...}, "cutting": {...}, ...}) as TOML text: top-level values
    first, then one [table] per dict (nested dicts as [table.sub])."""
    lines = []
    _table(scene, [], lines)
    return "\n".join(lines) + "\n"


def _table(d, path, lines):
    if not isinstance(d, dict):
        raise TypeError(f"a scene is a dict of tables, got {type(d).__name__}")
    tables = []
    for k, v in d.items():
        if isinstance(v, dict):
            tables.append((k, v))
        else:
            lines.append(f"{_key(k)} = {literal(v, '.'.join(path + [k]))}")
    for k, v in tables:
        lines.append("")
        lines.append("[" + ".".join(_key(p) for p in path + [k]) + "]")
        _table(v, path + [k], lines)
