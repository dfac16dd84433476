"""Where a config error is: the file, line and column of the key path that a config message starts with.

The config checks (the schema, :mod:`vcor.study.config`) name what is wrong by its key path,
``scenes.my-grid.grid.v0[0]: expected a number, got '36 km/h'``, on the merged mapping Snakemake made
of its config files. :func:`located` finds that path in the files themselves (the file that holds
most of it; on a tie the later one, as a later ``--configfile`` overrides an earlier one) and puts its
place in front::

    config file my.yaml, line 12, column 14: scenes.my-grid.grid.v0[0]: expected a number, got '36 km/h'

The path is the text before the message's first ": ", or its first word when that is a dotted path
(``materials.my-sls.E_glassy must be in (0, 1e+20] Pa, ...``). The place is that of the deepest part of
the path the file holds: the key of a mapping entry, or the item of a list (for a key that is not
allowed, the key itself). A message that does not start with a key path, or whose path no file holds,
is returned unchanged.
"""

from __future__ import annotations

import contextlib
import re
from pathlib import Path

__all__ = ["key_path", "locate", "located", "shown"]


_PATH = r"[^\[\]]+(\[\d+\]|\.[^.\[\]]+)*"
#: a path written as a message's first word: two or more parts, each without spaces or punctuation that
#: ends a word (a file name "data.csv," or a number "1.5" is not taken for one unless the file holds it)
_WORD_PATH = r"[^.\[\]\s,;:()]+(\[\d+\]|\.[^.\[\]\s,;:()]+)+"


def key_path(message: str) -> list | None:
    """The key path a config message starts with, as a list of names (str) and list indices (int): the text
    before its first ": " when it has no spaces (``scenes.s.grid.v0[0]: ...``), else its first word when
    that is a path of two or more parts (``materials.m.E[1] must be in ...``, ``materials.m (sls): ...``);
    None when it starts with neither."""
    found = _key_path(message)
    return None if found is None else found[0]


def _key_path(message: str):
    """(:func:`key_path`, whether it was the message's first word) or None."""
    head, sep, _ = message.partition(": ")
    word = not (sep and head and not any(c.isspace() for c in head))
    if word:
        head = message.split(" ", 1)[0] if " " in message else ""
    if not re.fullmatch(_WORD_PATH if word else _PATH, head):
        return None
    return [int(p[1:-1]) if p.startswith("[") else p for p in re.findall(r"\[\d+\]|[^.\[\]]+", head)], word


def _walk(node, keys: list):
    """(line, column), 1-based, of the deepest node of ``node`` along ``keys``, and how many keys were
    followed. A mapping key may itself hold dots: the longest run of parts that names a key is taken."""
    import yaml

    place, done, i = None, 0, 0
    while i < len(keys):
        if isinstance(node, yaml.SequenceNode) and isinstance(keys[i], int) and keys[i] < len(node.value):
            node = node.value[keys[i]]
            place, i = node.start_mark, i + 1
        elif isinstance(node, yaml.MappingNode) and isinstance(keys[i], str):
            names = {str(k.value): (k, v) for k, v in node.value}
            for j in range(len(keys), i, -1):
                parts = keys[i:j]
                if all(isinstance(p, str) for p in parts) and ".".join(parts) in names:
                    key_node, node = names[".".join(parts)]
                    place, i = key_node.start_mark, j
                    break
            else:
                break
        else:
            break
        done = i
    return (None if place is None else (place.line + 1, place.column + 1)), done


def locate(path, keys: list) -> tuple[tuple[int, int] | None, int]:
    """((line, column) or None, keys followed) of ``keys`` (:func:`key_path`) in the YAML file ``path``;
    (None, 0) when the file cannot be read or composed."""
    import yaml

    try:
        root = yaml.compose(Path(path).read_text(encoding="utf-8-sig"), Loader=getattr(yaml, "CSafeLoader",
                                                                                       yaml.SafeLoader))
    except (OSError, UnicodeDecodeError, yaml.YAMLError):
        return None, 0
    return _walk(root, keys) if root is not None else (None, 0)


def located(message: str, files) -> str:
    """``message`` with the place of its leading key path in front (module docstring): searched in
    ``files`` from the last; the file that holds most of the path wins, the later one on a tie."""
    found = _key_path(message)
    if not found or not found[0]:
        return message
    keys, word = found
    best, depth = None, 0
    for path in reversed(list(files)):
        place, done = locate(path, keys)
        # a first word is a key path only where the file holds all of it ("materials.csv does not exist")
        if place is not None and done > depth and (done == len(keys) or not word):
            best, depth = (path, place), done
    if best is None:
        return message
    path, (line, column) = best
    return f"config file {shown(path)}, line {line}, column {column}: {message}"


def shown(path) -> Path:
    """``path`` as a message shows it: relative to the working directory where it is inside it (Snakemake
    keeps its config files' paths absolute), else as it is."""
    with contextlib.suppress(ValueError):
        return Path(path).resolve().relative_to(Path.cwd().resolve())
    return Path(path)
