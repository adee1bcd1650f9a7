"""Writing a file so that its final name only ever holds a complete file.

The data go to a temporary file beside the target (same directory, so the same file system) that is
flushed to disk and then renamed over the target with :func:`os.replace`, which is atomic. If
anything fails on the way (a full disk, an error in the writer, Ctrl-C) the temporary file is
removed and the target is left as it
was: absent, or the previous complete file.

A target that exists and is not a regular file (``/dev/stdout``, ``/dev/full``, a FIFO) cannot be
replaced and is written in place; a symbolic link is followed, so the file it points to is replaced
and the link kept.
"""

from __future__ import annotations

import errno
import os
import secrets
import stat
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Iterator

#: Characters of the target's name kept in the temporary name (which adds about 25), so that a
#: target whose name fits the file system's 255-byte limit has a temporary name that fits too.
_NAME_KEPT = 200


@contextmanager
def replacing_path(path) -> Iterator[Path]:
    """Yield a temporary path for a writer that takes a file name (xarray, matplotlib); on success
    the file written there replaces ``path``. The temporary name keeps the target's suffix, for
    writers that choose their format by it. OSErrors name ``path``, not the temporary file."""
    target = Path(os.path.realpath(path))
    if _is_special(target):
        try:
            yield target
        except OSError as exc:
            raise _naming(exc, path, target) from exc
        return
    temporary = _create_beside(target, path)
    try:
        yield temporary
        _sync(temporary)
        os.replace(temporary, target)
    except BaseException as exc:
        _remove(temporary)
        if isinstance(exc, OSError):
            raise _naming(exc, path, temporary) from exc
        raise


@contextmanager
def replacing(path, mode: str = "w", **open_kwargs) -> Iterator[IO]:
    """``open(path, mode, **open_kwargs)`` for writing, through :func:`replacing_path`."""
    if "w" not in mode:
        raise ValueError(f"mode = {mode!r} is invalid: expected a writing mode ('w', 'wb')")
    with replacing_path(path) as temporary, open(temporary, mode, **open_kwargs) as f:
        yield f


def _is_special(target: Path) -> bool:
    try:
        return not stat.S_ISREG(os.stat(target).st_mode)
    except FileNotFoundError:
        return False


def _create_beside(target: Path, path) -> Path:
    """Create (exclusively, so no other writer shares it) an empty temporary file in the target's
    directory, with the permissions the target has, or else the ones a new file gets (0666 less the
    umask)."""
    try:
        mode = stat.S_IMODE(os.stat(target).st_mode)
    except FileNotFoundError:
        mode = None
    while True:
        temporary = target.with_name(
            f".{target.stem[:_NAME_KEPT]}.{secrets.token_hex(4)}.partial{target.suffix}"
        )
        try:
            fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:
            continue
        except OSError as exc:
            raise _naming(exc, path, temporary) from None
        try:
            if mode is not None and hasattr(
                os, "fchmod"
            ):  # POSIX: keep the replaced file's permissions
                os.fchmod(fd, mode)
        finally:
            os.close(fd)
        return temporary


def _sync(temporary: Path) -> None:
    """Flush the written data to disk before the rename, so a crash cannot leave a short file under
    the final name."""
    fd = os.open(
        temporary, os.O_RDWR if os.name == "nt" else os.O_RDONLY
    )  # Windows syncs writable handles
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _remove(temporary: Path) -> None:
    try:
        os.unlink(temporary)
    except FileNotFoundError:
        pass


def _naming(exc: OSError, path, temporary: Path) -> OSError:
    """The same error, naming the target instead of the temporary file (or naming it at all: a
    failed write names no file)."""
    if exc.filename not in (None, str(temporary), temporary):
        return exc
    code = exc.errno if exc.errno is not None else errno.EIO
    return OSError(code, exc.strerror or os.strerror(code), str(path))
