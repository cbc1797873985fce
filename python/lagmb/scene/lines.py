"""Line numbers of the tables and keys of a TOML text, for error messages.

tomllib gives the data but not where each part of it stands; ``Lines`` scans
the text (already accepted by tomllib, or about to be checked by it) line by
line: table headers, keys, and enough of each value (strings, comments,
brackets) to know where it ends and how deeply it nests.
"""

import json
import re

from .schema import MAX_NESTING

BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def _read_key(s, pos):
    """The dotted key starting at s[pos]: (list of parts, position after it)."""
    parts = []
    n = len(s)
    while True:
        while pos < n and s[pos] in " \t":
            pos += 1
        if pos >= n:
            return parts, pos
        if s[pos] == '"':
            j = pos + 1
            while j < n and s[j] != '"':
                j += 2 if s[j] == "\\" else 1
            try:
                parts.append(json.loads(s[pos:j + 1]))
            except ValueError:
                parts.append(s[pos + 1:j])
            pos = j + 1
        elif s[pos] == "'":
            j = s.find("'", pos + 1)
            j = n if j < 0 else j
            parts.append(s[pos + 1:j])
            pos = j + 1
        else:
            m = BARE_KEY.match(s, pos)
            if m is None:
                return parts, pos
            parts.append(m.group())
            pos = m.end()
        while pos < n and s[pos] in " \t":
            pos += 1
        if pos < n and s[pos] == ".":
            pos += 1
            continue
        return parts, pos


class Lines:
    """Line numbers of the tables and keys of a TOML text (which tomllib has
    already accepted): ``line(path)`` for a path of keys and array indices as
    in the parsed data, e.g. ("joints", 2, "at"), or of its nearest parent."""

    def __init__(self, text):
        self.at = {}
        self._arrays = {}  # path of an array of tables -> entries so far
        self._table = ()
        self._depth = 0  # open [ and { of a value spanning lines
        self._string = None  # delimiter of an open multi-line string
        self._number = 0  # the line being scanned
        self._key = ()  # the path of the key whose value is being scanned
        self.too_deep = None  # (line, key path) where values nest deeper than MAX_NESTING
        try:
            self._scan(text)
        except Exception:  # noqa: BLE001 - line numbers are a help, never a failure
            pass

    def line(self, path):
        path = tuple(path)
        while path:
            if path in self.at:
                return self.at[path]
            path = path[:-1]
        return None

    def key_at(self, line):
        """The path of the key (or table) given last on or before a line, for
        errors found before the data exists (tomllib's, the nesting check)."""
        best = ()
        for path, number in self.at.items():
            if number <= line and (not best or (number, len(path)) >= (self.at[best], len(best))):
                best = path
        return best

    def _resolve(self, parts):
        out = ()
        for p in parts:
            out += (p,)
            if out in self._arrays:
                out += (self._arrays[out] - 1,)
        return out

    def _scan(self, text):
        for number, line in enumerate(text.split("\n"), 1):
            self._number = number
            if line.endswith("\r"):
                line = line[:-1]
            if self._string is not None or self._depth > 0:
                self._scan_value(line, 0)
                continue
            s = line.lstrip(" \t")
            if not s or s[0] == "#":
                continue
            if s.startswith("[["):
                parts, _ = _read_key(s, 2)
                array = self._resolve(parts[:-1]) + (parts[-1],)
                self.at.setdefault(array, number)
                self._arrays[array] = self._arrays.get(array, 0) + 1
                self._table = array + (self._arrays[array] - 1,)
                self.at[self._table] = number
            elif s[0] == "[":
                parts, _ = _read_key(s, 1)
                self._table = self._resolve(parts)
                for k in range(1, len(self._table) + 1):
                    self.at.setdefault(self._table[:k], number)
            else:
                parts, pos = _read_key(s, 0)
                for k in range(1, len(parts) + 1):
                    self.at.setdefault(self._table + tuple(parts[:k]), number)
                self._key = self._table + tuple(parts)
                eq = s.find("=", pos)
                self._scan_value(s, eq + 1 if eq >= 0 else len(s))

    def _scan_value(self, s, i):
        """Follow strings, comments and brackets to the end of the line."""
        n = len(s)
        while i < n:
            if self._string is not None:
                if self._string == '"""' and s[i] == "\\":
                    i += 2
                elif s.startswith(self._string, i):
                    i += 3
                    while i < n and s[i] == self._string[0]:
                        i += 1
                    self._string = None
                else:
                    i += 1
                continue
            c = s[i]
            if c == "#":
                return
            if s.startswith('"""', i) or s.startswith("'''", i):
                self._string = s[i:i + 3]
                i += 3
            elif c == '"':
                i += 1
                while i < n and s[i] != '"':
                    i += 2 if s[i] == "\\" else 1
                i += 1
            elif c == "'":
                j = s.find("'", i + 1)
                i = n if j < 0 else j + 1
            else:
                if c in "[{":
                    self._depth += 1
                    if self._depth > MAX_NESTING and self.too_deep is None:
                        self.too_deep = (self._number, self._key)
                elif c in "]}":
                    self._depth -= 1
                i += 1

