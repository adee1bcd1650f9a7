"""Reading an input file whole, or refusing it: never a hang, never a silent truncation.

A FIFO, a device or a directory given as an input would block or stream without end, so only
regular files are read (checked on the open descriptor, which is opened non-blocking so that a FIFO
without a writer does not hang the open itself). A file larger than the reader's limit is an error,
not its first part. A UTF-8 byte-order mark, which some editors write, is dropped. Numbers in
files and options are read as ASCII decimals only (:func:`number`, :func:`integer`).
"""

from __future__ import annotations

import os
import re
import stat
from typing import Optional

BOM = b"\xef\xbb\xbf"


def read_bytes(path, max_bytes: int, noun: str, expected: str) -> bytes:
    """The bytes of the regular file ``path``, at most ``max_bytes`` of them; ValueError naming
    ``path``, ``noun`` (what is read, as in "cannot read the scenario") and ``expected``, what the
    file should be, otherwise."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise ValueError(f"{path}: cannot read {noun}: {exc.strerror or exc}") from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise ValueError(
                f"{path}: cannot read {noun}: {_kind(mode)}, not a regular file: expected "
                f"{expected}"
            )
        with os.fdopen(fd, "rb", closefd=False) as f:
            data = f.read(max_bytes + 1)
    except OSError as exc:
        raise ValueError(f"{path}: cannot read {noun}: {exc.strerror or exc}") from None
    finally:
        os.close(fd)
    if len(data) > max_bytes:
        raise ValueError(
            f"{path}: the file is larger than {max_bytes:,} bytes: expected {expected}; "
            "nothing of it was read"
        )
    return data


def read_text(path, max_bytes: int, noun: str, expected: str) -> str:
    """:func:`read_bytes` decoded as UTF-8, a leading byte-order mark dropped; ValueError naming
    the first byte that is not UTF-8."""
    data = read_bytes(path, max_bytes, noun, expected)
    if data.startswith(BOM):
        data = data[len(BOM) :]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValueError(
            f"{path}: not UTF-8 text: byte {exc.start} (0x{data[exc.start]:02x}); "
            f"expected {expected}"
        ) from None


def _kind(mode: int) -> str:
    for test, name in (
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return name
    return "a special file"


#: A number as the project's files and options write it: ASCII digits, '.' as the decimal point,
#: an optional exponent, or nan/inf. Python's float() also takes full-width and other Unicode
#: digits and '_' between digits, which a file or an option would then mean something else by.
_NUMBER = re.compile(r"[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|nan|inf|infinity)\Z", re.I)
_INTEGER = re.compile(r"[+-]?\d+\Z")


def number(text: str) -> Optional[float]:
    """``text`` (surrounding blanks ignored) as a float when it is an ASCII decimal number, else
    None: no Unicode digits, no '_' separators, no decimal comma."""
    text = text.strip()
    if not text.isascii() or not _NUMBER.match(text):
        return None
    return float(text)


def integer(text: str) -> Optional[int]:
    """``text`` (surrounding blanks ignored) as an int when it is ASCII digits with an optional
    sign, else None."""
    text = text.strip()
    if not text.isascii() or not _INTEGER.match(text):
        return None
    return int(text)
