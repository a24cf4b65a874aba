"""Result files as documents: the HTML report of a result and the merge of the parts of a map
or study computed as a batch job (the command line's ``flaplag report`` and ``flaplag merge``,
the same C++ code and the same bytes)."""

import os

from . import _flaplag
from ._analysis import InvalidInput, _invalid, _memory_limit


def _path(field, value, allow_none=False):
    """A file path as text from a str or os.PathLike (None: "" when allowed)."""
    if value is None and allow_none:
        return ""
    try:
        path = os.fspath(value)
    except TypeError:
        path = None
    if not isinstance(path, str) or not path:
        raise _invalid(InvalidInput, field, value, "must be a file path (str or os.PathLike)")
    return path


def report(result, html=None, memory_limit=None):
    """The one-page HTML report of a result file (a ``--json`` output of flaplag, e.g. of
    ``flaplag critical --json -o a.json``), as ``flaplag report a.json`` makes it: the outcome,
    the key results, the model, the inputs, the convergence evidence, the pictures (drawn by
    gnuplot when installed), every warning and the provenance.  Every text of the file is
    HTML-escaped and the page runs no script.

    html: the path of the page, written atomically (None: not written).  memory_limit: as
    flaplag.map's (bytes or a size such as '8G'; the file is read within 1/16 of it).  Returns
    the page as text.  A file that cannot be read, is not JSON or not a flaplag result raises
    flaplag.InvalidInput naming the argument ("result = a.json: not JSON ...")."""
    return _flaplag.report(
        _path("result", result), _path("html", html, allow_none=True), _memory_limit(memory_limit)
    )


def merge(parts, output=None, memory_limit=None):
    """The parts of a map or study computed with ``--shard I/N`` (``flaplag map ... --json
    --shard 1/4 -o part-1.json``, ...) joined, in any order, into exactly the JSON text one run
    of the whole job writes, as ``flaplag merge`` does: each part is checked against its case
    (digest, block, axis values, shapes, labels, the model and parameters its case computes).

    parts: a list of file paths.  output: the path of the merged file, written atomically (None:
    not written).  memory_limit: as flaplag.map's.  Returns the merged JSON text.  A part that is
    missing, repeated, damaged or of another case raises flaplag.InvalidInput naming the
    argument ("parts = part-2.json: ...")."""
    if isinstance(parts, (str, bytes)) or not hasattr(parts, "__iter__"):
        raise _invalid(InvalidInput, "parts", parts, "must be a list of file paths")
    paths = [_path("parts", p) for p in parts]
    if not paths:
        raise _invalid(InvalidInput, "parts", parts, "no parts given")
    return _flaplag.merge(
        paths, _path("output", output, allow_none=True), _memory_limit(memory_limit)
    )
