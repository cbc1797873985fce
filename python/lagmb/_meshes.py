"""Meshes lagmb reads: the triangles of an STL file (binary or ASCII), for
the pictures (lagmb.plotting.picture) and the browser viewer (lagmb.view).
Other formats (COLLADA, OBJ) are not read; their shapes are left out."""

import math
import os
import re

import numpy as np

from ._checks import decimal, show
from .errors import ModelError


def read_stl(path):
    """The triangles (n, 3, 3) of an STL file, binary or ASCII (m). A
    ModelError names the file and what is wrong with it: a binary file whose
    size is not its triangle count's (cut short, or a count past its end),
    an ASCII one cut short or holding a word where a keyword or a number
    belongs, a vertex that is not finite."""
    who = f"STL file {os.fspath(path)!r}"
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise ModelError(f"{who}: cannot read it: {e.strerror or e}") from None
    count = int.from_bytes(data[80:84], "little") if len(data) >= 84 else None
    if count is not None and 84 + 50 * count == len(data):  # binary: 80-byte header, count, 50 bytes per triangle
        records = np.frombuffer(data, dtype=np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)),
                                                      ("attribute", "<u2")]), count=count, offset=84)
        triangles = records["vertices"].astype(float)
        bad = np.flatnonzero(~np.isfinite(triangles).all(axis=(1, 2)))
        if len(bad):
            raise ModelError(f"{who}: triangle {bad[0] + 1} of {count} has a vertex that is not finite: "
                             f"{show(triangles[bad[0]].tolist())}")
        return triangles
    # ASCII starts with "solid"; so do some binary headers, but binary floats hold zero bytes
    if data.lstrip()[:5].lower() == b"solid" and b"\0" not in data:
        return _read_ascii_stl(data.decode("ascii", errors="replace"), who)
    if count is None:
        raise ModelError(f"{who}: {len(data)} bytes: too short for a binary STL (80 bytes of header and a "
                         "triangle count) and not an ASCII one (which starts with 'solid')")
    raise ModelError(f"{who}: a binary STL of {count} triangles (as its bytes 80..83 say) is 84 + 50 x {count} = "
                     f"{84 + 50 * count} bytes long; the file has {len(data)} bytes"
                     + (" (cut short, or a wrong count?)" if len(data) < 84 + 50 * count else ""))


# One facet of an ASCII STL, word by word (None: a number): its normal (not
# used), then its three vertices.
_FACET = ("facet", "normal", None, None, None, "outer", "loop", "vertex", None, None, None, "vertex", None, None,
          None, "vertex", None, None, None, "endloop", "endfacet")


def _read_ascii_stl(text, who):
    """The triangles of an ASCII STL's text: solids ('solid' name ...
    'endsolid' name) of facets as _FACET spells them."""
    # a solid's name is the rest of its line (it may hold any word)
    text = re.sub(r"(?im)^([ \t]*(?:end)?solid)\b[^\n]*", r"\1", text)
    words = text.split()
    n = len(words)

    def where(i):  # the line of word i: worked out only for a message
        seen = 0
        for line, words_in in enumerate(text.split("\n"), 1):
            seen += len(words_in.split())
            if seen > i:
                return f"{who}, line {line}"
        return who

    def wrong(i, wanted):
        if i >= n:
            return ModelError(f"{who}: ends (line {len(text.rstrip().split(chr(10)))}) where {wanted} belongs "
                              "(cut short?)")
        return ModelError(f"{where(i)}: {show(words[i])} where {wanted} belongs")

    def number(i):
        try:
            return decimal(words[i], who)
        except ModelError:
            return decimal(words[i], where(i))  # raises again, its message naming the line

    def keyword(i, wanted):
        if i >= n or (words[i] != wanted and words[i].lower() != wanted):
            raise wrong(i, repr(wanted))

    vertices = []
    i = 0
    while i < n:
        keyword(i, "solid")
        i += 1
        while i >= n or words[i].lower() != "endsolid":
            if i >= n or words[i].lower() != "facet":
                raise wrong(i, "'facet' or 'endsolid'")
            for j, wanted in enumerate(_FACET):
                if wanted is not None:
                    keyword(i + j, wanted)
                elif i + j >= n:
                    raise wrong(i + j, "a number")
                else:
                    x = number(i + j)
                    if j > 4:  # a vertex's coordinate
                        if not math.isfinite(x):
                            raise ModelError(f"{where(i + j)}: a vertex coordinate {show(words[i + j])} is not finite")
                        vertices.append(x)
            i += len(_FACET)
        i += 1
    return np.array(vertices, dtype=float).reshape(-1, 3, 3)
