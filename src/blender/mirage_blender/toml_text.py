"""A scene or shader document (the dict Scene.from_dict takes) as TOML text, so that what the
add-on renders can be written out and rendered by `mirage render` (docs/blender.md, "Export").

Only what the exporter makes: tables of numbers, strings, booleans, lists of them, inline
tables, and arrays of tables. Python 3.11's tomllib reads TOML but does not write it.
"""
import json
import math


def _scalar(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"{v} has no TOML number")
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)  # a TOML basic string is a JSON string
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_scalar(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {_scalar(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"no TOML form for {type(v).__name__}")


def _is_table_array(v):
    return isinstance(v, list) and v and all(isinstance(x, dict) for x in v)


def _table(lines, header, table):
    """One table: its plain keys, then its sub-tables and arrays of tables."""
    plain = {k: v for k, v in table.items()
             if not isinstance(v, dict) and not _is_table_array(v)}
    if header and (plain or not table):
        lines.append(f"[{header}]")
    for k, v in plain.items():
        lines.append(f"{k} = {_scalar(v)}")
    if plain or (header and not table):
        lines.append("")
    for k, v in table.items():
        name = f"{header}.{k}" if header else k
        if isinstance(v, dict):
            _table(lines, name, v)
        elif _is_table_array(v):
            for item in v:
                lines.append(f"[[{name}]]")
                for ik, iv in item.items():
                    lines.append(f"{ik} = {_scalar(iv)}")
                lines.append("")


def dumps(document):
    """TOML text of `document`: top-level keys first, then one table per dict, and arrays of
    tables as [[name]] blocks (their own dicts inline)."""
    lines = []
    _table(lines, "", document)
    return "\n".join(lines).rstrip("\n") + "\n"
