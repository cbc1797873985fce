"""The store of a parameter study (``mb.sweep(..., store=)``, ``lagmb sweep
-o``): a Zarr folder holding the sweep's description in its root
attributes and one group per finished batch, each with a marker of its
files written last, so that a batch is whole or is computed again; a lock
file keeps a second sweep out while one writes. lagmb.studies.study runs
the cases and hands each batch's Dataset here; ``check_store`` and
``open_store`` are public as ``lagmb.studies``'s (docs/api.rst).
"""

import errno
import hashlib
import json
import math
import os
import re
import shutil
import socket
import threading
import uuid
import warnings

from .._checks import show
from ..errors import ModelError, extra_module

# at most this many cases in one sweep or design: a typo (0:1:1e9, n=10**12)
# is refused, not a machine filled with case lists (memory is checked too);
# a store's description that claims more is damaged
MAX_CASES = 10_000_000
_FORMAT = 2  # 2: each batch's marker of its files, the outputs' descriptions, the lock


def description(made_of, cases, batch_size, outputs, grid):
    """What a sweep writes into its store's root attributes: the format,
    what the sweep is made of (lagmb.studies: the digests of its model,
    cases, settings and outputs) and its fingerprint, its number of cases,
    batch size, output names and grid (as the Dataset's attrs["grid"])."""
    return {"format": _FORMAT, "fingerprint": _fingerprint(made_of), "made_of": made_of, "cases": cases,
            "batch_size": batch_size, "outputs": list(outputs), "grid": grid}


def _fingerprint(made_of):
    return hashlib.sha256(json.dumps(made_of, sort_keys=True).encode()).hexdigest()


def _differences(held, made_of):
    """What differs between the sweep a store holds and this one, in words."""
    if not isinstance(held, dict):
        return "another model, cases, settings or outputs"
    words = [f"another {part}" if part == "model" else f"other {part}" for part in
             ("model", "cases", "settings", "histories") if held.get(part) != made_of[part]]
    there, here = held.get("outputs") if isinstance(held.get("outputs"), dict) else {}, made_of["outputs"]
    changed = [f"{name}: {there.get(name, 'none')} there, {here.get(name, 'none')} here"
               for name in dict.fromkeys(list(there) + list(here)) if there.get(name) != here.get(name)]
    if changed:
        words.append("other outputs (" + "; ".join(changed) + ")")
    return ", ".join(words) or "another sweep"


_LOCK = "lagmb_sweep.lock"  # held by the sweep writing the store
_MARKER = "lagmb_batch"     # a batch group's attribute, written last: its files; a batch without it is not whole
_BATCH = re.compile(r"batch_([0-9]{6,})")
_TMP = re.compile(r"tmp_[0-9]{6,}_[0-9a-f]{32}")  # a batch being written (this module's names only)
_ZARR = ("zarr.json", ".zgroup", ".zattrs", ".zarray", ".zmetadata")


def _held(path, who):
    """The description in the store's root attributes (None if the Zarr
    store has none); ModelError naming the store if it cannot be read."""
    zarr = extra_module("zarr", "sweep", f"{who}'s store")

    try:
        held = zarr.open_group(path, mode="r").attrs.get("lagmb_sweep")
    except Exception as e:  # noqa: BLE001 - JSONDecodeError, GroupNotFoundError, ...: damaged
        raise ModelError(f"{who}: the store {path!r} cannot be read: its zarr.json is damaged "
                         f"({type(e).__name__}: {' '.join(str(e).split())[:200]})") from None
    if held is None:
        return None
    if not isinstance(held, dict) or held.get("format") != _FORMAT:
        made = held.get("format") if isinstance(held, dict) else None
        raise ModelError(f"{who}: the store {path!r} was written by another version of lagmb (store format "
                         f"{show(made)}; this one reads format {_FORMAT}): delete it to start again")
    checks = {"fingerprint": lambda v: isinstance(v, str),
              "cases": lambda v: isinstance(v, int) and not isinstance(v, bool) and 1 <= v <= MAX_CASES,
              "batch_size": lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= 1,
              "outputs": lambda v: isinstance(v, list) and all(isinstance(x, str) for x in v),
              "grid": lambda v: isinstance(v, str), "made_of": lambda v: isinstance(v, dict)}
    for key, good in checks.items():
        if not good(held.get(key)):
            raise ModelError(f"{who}: the store {path!r} cannot be read: its description is damaged "
                             f"({key}: {show(held.get(key))})")
    return held


def _path(given, who):
    try:
        path = os.fspath(given)
    except TypeError:
        path = None
    if not isinstance(path, str):
        raise ModelError(f"{who}: the store must be a folder's path (a str or a pathlib.Path), got {show(given)}")
    return path


def check_store(path, who="sweep", writing=True):
    """The description of the sweep the store at ``path`` holds, or None
    where a sweep may make one (no such folder, or an empty one). A
    ModelError if ``path`` is a file, a folder that is not a sweep's store
    (a sweep writes into no other folder: another program's Zarr store
    included) or a store that cannot be read. mb.sweep and ``lagmb sweep
    -o`` both check a store with it, before anything is written
    (``writing``: the message says to give another folder); open_store too."""
    path = _path(path, who)
    if os.path.lexists(path) and not os.path.isdir(path):
        raise ModelError(f"{who}: the store {path!r} is a file; a store is a folder (e.g. study.zarr)")
    if not os.path.isdir(path):
        return None
    try:
        names = set(os.listdir(path)) - {_LOCK}
    except OSError as e:
        raise ModelError(f"{who}: the store {path!r} cannot be read: {e.strerror or e}") from None
    if not names:
        return None
    if not names & set(_ZARR):
        if _LOCK in os.listdir(path) or any(_BATCH.fullmatch(name) for name in names):
            raise ModelError(f"{who}: the store {path!r} cannot be read: its zarr.json is missing (copied in "
                             "part?): delete it to start again")
        raise ModelError(f"{who}: {path!r} is a folder that is not a study's store"
                         + (": give a new folder name (e.g. study.zarr); a sweep writes into no other folder"
                            if writing else ""))
    held = _held(path, who)
    if held is None:
        raise ModelError(f"{who}: {path!r} is a Zarr store, but not a study's (lagmb sweep's)"
                         + (": give a new folder name; a sweep writes into no other store" if writing else ""))
    return held


_GROUP_ATTRIBUTES = ("zarr.json", ".zattrs")  # where a group's attributes are (Zarr 3, Zarr 2): the marker's


def _files(folder):
    """{path in folder: [size, sha256]} of the batch group's files but the
    one holding its attributes (and so its marker)."""
    files = {}
    for root, dirs, names in os.walk(folder):
        dirs.sort()
        for name in sorted(names):
            full = os.path.join(root, name)
            relative = os.path.relpath(full, folder).replace(os.sep, "/")
            if relative not in _GROUP_ATTRIBUTES:
                with open(full, "rb") as fh:
                    data = fh.read()
                files[relative] = [len(data), hashlib.sha256(data).hexdigest()]
    return files


def _marker(folder):
    """The batch group's marker (None if it has none), read from its
    attributes' file as JSON: quicker than opening the group with zarr."""
    for name in _GROUP_ATTRIBUTES:
        try:
            with open(os.path.join(folder, name), encoding="utf-8") as fh:
                held = json.load(fh)
        except FileNotFoundError:
            continue
        attributes = held.get("attributes", {}) if name == "zarr.json" and isinstance(held, dict) else held
        return attributes.get(_MARKER) if isinstance(attributes, dict) else None
    return None


def _batch_problem(folder, fingerprint, batch, first, last):
    """Why the batch folder is not whole (None if it is): no marker (not
    finished, or copied in part), another sweep's or another batch's, a file
    missing, changed or added."""
    try:
        marker = _marker(folder)
    except (OSError, ValueError) as e:
        return f"its attributes cannot be read ({type(e).__name__})"
    if marker is None:
        return "it has no marker of its files (it was not finished, or was copied in part)"
    if not isinstance(marker, dict) or not isinstance(marker.get("files"), dict):
        return "its marker is damaged"
    if [marker.get(k) for k in ("fingerprint", "batch", "first", "last")] != [fingerprint, batch, first, last]:
        return "it holds another sweep's cases, or another batch's (copied in?)"
    try:
        found = _files(folder)
    except OSError as e:
        return f"its files cannot be read ({e.strerror or e})"
    for name, size_hash in marker["files"].items():
        if name not in found:
            return f"its file {name} is missing"
        if found[name] != size_hash:
            return f"its file {name} differs from what was written"
    added = [name for name in found if name not in marker["files"] and not os.path.basename(name).startswith(".")]
    if added:
        return f"it holds a file the sweep did not write ({added[0]})"
    return None


def scan(path, held):
    """(whole, damaged, ignored) of a store's batch folders: whole {batch:
    (first, last)}, damaged {batch: why not whole}, ignored [names of
    folders that are no batch of this study, e.g. beyond its cases]."""
    n, size = held["cases"], held["batch_size"]
    count = math.ceil(n / size)
    whole, damaged, ignored = {}, {}, []
    for name in sorted(os.listdir(path)):
        if not name.startswith("batch_"):
            continue
        match = _BATCH.fullmatch(name)
        batch = int(match.group(1)) if match else -1
        if not 0 <= batch < count:
            ignored.append(name)
            continue
        first, last = batch * size, min(n, (batch + 1) * size)
        problem = _batch_problem(os.path.join(path, name), held["fingerprint"], batch, first, last)
        if problem is None:
            whole[batch] = (first, last)
        else:
            damaged[batch] = f"{name} (cases {first}..{last - 1}): {problem}"
    return whole, damaged, ignored


_HELD = set()  # the lock files this process holds: a POSIX lock does not stop the process that holds it
_HELD_GUARD = threading.Lock()


class Lock:
    """The store's lock file, locked while a sweep writes the store and
    holding its pid: a second sweep on the store (of another process, or of
    this one) is refused naming it. A POSIX record lock (fcntl.lockf; on
    Windows msvcrt.locking) belongs to the process, not to its open file:
    the system lets go of it when the process ends, forked worker processes
    included, so the lock file of a process that is gone is taken over."""

    def __init__(self, folder, who):
        self.path = os.path.realpath(os.path.join(folder, _LOCK))
        self.fd, self.locked = None, False
        with _HELD_GUARD:
            if self.path in _HELD:
                raise ModelError(f"{who}: the store {folder!r} is in use by another sweep (pid {os.getpid()}, this "
                                 "process): let it finish, or give another store")
            try:
                self.fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o666)
            except OSError as e:
                raise ModelError(f"{who}: the store {folder!r} cannot be written: {e.strerror or e}") from None
            try:
                self._lock(True)
            except OSError as e:
                if e.errno not in (errno.EAGAIN, errno.EACCES, errno.EWOULDBLOCK, errno.EDEADLK):
                    # a file system without locks (some network mounts): go on, unguarded
                    warnings.warn(f"{who}: the store {folder!r} cannot be locked ({e.strerror or e}): run no "
                                  "other sweep on it meanwhile", UserWarning, stacklevel=4)
                    _HELD.add(self.path)
                    return
                os.lseek(self.fd, 0, os.SEEK_SET)
                holder = os.read(self.fd, 200).decode(errors="replace").split()
                os.close(self.fd)
                here = socket.gethostname()
                whose = (f"pid {holder[0]}" + (f" on {holder[1]}" if len(holder) > 1 and holder[1] != here else "")
                         if holder else "pid unknown")
                raise ModelError(f"{who}: the store {folder!r} is in use by another sweep ({whose}): let it "
                                 "finish, or give another store") from None
            self.locked = True
            _HELD.add(self.path)
        os.ftruncate(self.fd, 0)
        os.lseek(self.fd, 0, os.SEEK_SET)
        os.write(self.fd, f"{os.getpid()} {socket.gethostname()}\n".encode())

    def _lock(self, take):
        # a byte far past the pid: Windows's lock keeps others from reading the bytes it covers
        try:
            import fcntl
        except ImportError:
            import msvcrt

            os.lseek(self.fd, 1 << 20, os.SEEK_SET)
            try:
                msvcrt.locking(self.fd, msvcrt.LK_NBLCK if take else msvcrt.LK_UNLCK, 1)
            finally:
                os.lseek(self.fd, 0, os.SEEK_SET)
            return
        fcntl.lockf(self.fd, (fcntl.LOCK_EX | fcntl.LOCK_NB) if take else fcntl.LOCK_UN, 1, 1 << 20)

    def release(self):
        try:
            if self.locked:
                self._lock(False)
        finally:
            os.close(self.fd)
            with _HELD_GUARD:
                _HELD.discard(self.path)


class Store:
    """A Zarr directory store: the sweep's description in the root
    attributes, and one group per finished batch ("batch_000012"), written
    under a temporary name, its marker of files last, then renamed: a batch
    is whole when its marker says so. The store is locked while a sweep
    writes it."""

    def __init__(self, path, description, who):
        zarr = extra_module("zarr", "sweep", f"{who}'s store")

        self.path, self.who = _path(path, who), who
        check_store(self.path, who)  # before anything is written: nothing into a folder of another's
        try:
            os.makedirs(self.path, exist_ok=True)
        except OSError as e:
            raise ModelError(f"{who}: the store {self.path!r} cannot be made: {e.strerror or e}") from None
        self.lock = Lock(self.path, who)
        try:
            held = check_store(self.path, who)  # again under the lock: another sweep may have made it meanwhile
            if held is None:
                try:
                    zarr.open_group(self.path, mode="a").attrs["lagmb_sweep"] = description
                except OSError as e:
                    raise ModelError(f"{who}: the store {self.path!r} cannot be written: {e.strerror or e}"
                                     ) from None
                held = description
            elif held["fingerprint"] != description["fingerprint"]:
                raise ModelError(f"{who}: the store {self.path!r} holds another sweep (made with "
                                 f"{_differences(held['made_of'], description['made_of'])}): give another store, "
                                 "or delete this one to start again")
            self.held = held
            for name in os.listdir(self.path):  # the leftovers of a batch interrupted while written
                if _TMP.fullmatch(name):
                    shutil.rmtree(os.path.join(self.path, name), ignore_errors=True)
        except BaseException:
            self.lock.release()
            raise

    def write(self, batch, first, last, ds):
        """The batch's Dataset into the store: whole, or not there."""
        tmp = os.path.join(self.path, f"tmp_{batch:06d}_{uuid.uuid4().hex}")
        import zarr

        ds.to_zarr(self.path, group=os.path.basename(tmp), mode="w", consolidated=False)
        marker = {"fingerprint": self.held["fingerprint"], "batch": batch, "first": first, "last": last,
                  "files": _files(tmp)}
        zarr.open_group(tmp, mode="r+").attrs[_MARKER] = marker  # last: the batch is whole
        target = os.path.join(self.path, f"batch_{batch:06d}")
        if os.path.lexists(target) and not os.path.isdir(target):
            os.remove(target)  # a file under a batch's name: not a batch
        if os.path.isdir(target):
            if _batch_problem(target, self.held["fingerprint"], batch, first, last) is None:
                shutil.rmtree(tmp, ignore_errors=True)  # already there and whole: nothing to do
                return
            old = os.path.join(self.path, f"tmp_{batch:06d}_{uuid.uuid4().hex}")  # a damaged one: replaced
            os.rename(target, old)
            shutil.rmtree(old, ignore_errors=True)
        os.rename(tmp, target)

    def close(self):
        self.lock.release()


def open_store(path):
    """The Dataset of a sweep's store (what ``mb.sweep(..., store=path)``
    wrote), its finished cases in case order. A batch that is not whole (not
    finished, copied in part, changed) or no batch of the study (a folder
    beyond its cases) is left out with a warning naming it; the sweep run
    again computes it. A folder that is no sweep's store, or a store that
    cannot be read, is a ModelError naming it and what is wrong."""
    who = "sweep.open_store"
    path = _path(path, who)
    if not os.path.isdir(path):
        raise ModelError(f"{who}: no store at {path!r}")
    held = check_store(path, who, writing=False)
    if held is None:
        raise ModelError(f"{who}: {path!r} is not a sweep's store (an empty folder)")
    whole, damaged, ignored = scan(path, held)
    if ignored:
        ignored_warning(path, held, ignored, who, stacklevel=2)
    return read(path, held, whole, damaged, who, "left out (the sweep run again computes them)", stacklevel=2)


def ignored_warning(path, held, ignored, who, stacklevel):
    count = math.ceil(held["cases"] / held["batch_size"])
    warnings.warn(f"{who}: the store {path!r}: {', '.join(ignored)} "
                  f"{'is no batch' if len(ignored) == 1 else 'are no batches'} of its study ({held['cases']:,} "
                  f"cases in batches batch_000000..batch_{count - 1:06d}): left out", UserWarning,
                  stacklevel=stacklevel + 1)


def read(path, held, whole, damaged, who, fate, stacklevel):
    """The Dataset of the store's whole batches; the damaged ones (and those
    that cannot be read) named in a warning, with their fate."""
    xr = extra_module("xarray", "sweep", who)

    damaged = dict(damaged)
    parts = []
    for batch, (first, last) in sorted(whole.items()):
        name = f"batch_{batch:06d}"
        try:
            part = xr.open_zarr(path, group=name, consolidated=False).load()
            if list(part["case"].values) != list(range(first, last)):
                raise ValueError(f"its cases are {show(list(part['case'].values))}")
        except Exception as e:  # noqa: BLE001 - a chunk that cannot be decoded, ...: named, left out
            damaged[batch] = (f"{name} (cases {first}..{last - 1}): it cannot be read ({type(e).__name__}: "
                              f"{' '.join(str(e).split())[:200]})")
            continue
        parts.append(part)
    if damaged:
        warnings.warn(f"{who}: the store {path!r}: " + "; ".join(damaged[b] for b in sorted(damaged)) + f": {fate}",
                      UserWarning, stacklevel=stacklevel + 1)
    if not parts:
        raise ModelError(f"{who}: {path!r} holds no finished case yet")
    ds = xr.concat(parts, dim="case").sortby("case")
    # the variables in the order a sweep makes them (a store lists them by name)
    order = ["status", "warnings", "steps", "wall_time"] + list(held["outputs"]) + ["q"]
    ds = ds[[v for v in order if v in ds.data_vars] + [v for v in ds.data_vars if v not in order]]
    ds.attrs = {"grid": held["grid"]}  # not the batches' markers
    return ds
