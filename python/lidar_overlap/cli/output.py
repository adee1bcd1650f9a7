"""What the commands print besides their results: warnings collected and printed once after
success, notes about outputs left out, the one-line failure, and the progress of a long run."""

from __future__ import annotations

import sys
import warnings
from contextlib import contextmanager

PROG = "lidar-overlap"
#: The longest error line printed (a message quoting a large value is cut there).
MAX_MESSAGE = 1000


def progress(label: str, total: int):
    """A callback(number_done) drawing a tqdm bar if installed, else a counter on stderr, and its
    closer close(completed), which erases the counter of a failed run so that the error stays the
    only line."""
    try:
        from tqdm import tqdm
    except ImportError:

        def show(done):
            print(f"\r{label}: {done}/{total} ranges", end="", file=sys.stderr, flush=True)

        def close(completed):
            blank = " " * len(f"{label}: {total}/{total} ranges")
            print(
                "" if completed else f"\r{blank}\r",
                end="\n" if completed else "",
                file=sys.stderr,
                flush=True,
            )

        return show, close
    bar = tqdm(total=total, desc=label, unit="range", file=sys.stderr, leave=False)
    return lambda done: bar.update(done - bar.n), lambda completed: bar.close()


class Note(UserWarning):
    """An output left out (an optional dependency missing), printed as "note: ..." with the
    warnings."""


def noted(written_and_note):
    """The path of a (path, note) pair, the note (an output left out) raised as a :class:`Note`."""
    path, note = written_and_note
    if note:
        warnings.warn(note, Note, stacklevel=2)
    return path


@contextmanager
def printed_warnings():
    """Collect the warnings of a block and print them, one line each and each once, if the block
    succeeds (a failure prints its error alone). Runtime warnings are always shown, whatever filters
    the caller set."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        warnings.simplefilter("always", UserWarning)
        yield
    kinds = {Note: "note"}
    lines = (f"{kinds.get(w.category, 'warning')}: {one_line(str(w.message))}" for w in caught)
    for line in dict.fromkeys(lines):  # each once, in order
        print(line, file=sys.stderr)


def fail(message: str, code: int) -> int:
    line = one_line(str(message))
    if len(line) > MAX_MESSAGE:
        line = f"{line[: MAX_MESSAGE - 3]}..."
    print(f"{PROG}: error: {line}", file=sys.stderr)
    return code


def one_line(text: str) -> str:
    """``text`` on one line, without control characters (a scenario's text must not drive the
    terminal)."""
    return " ".join("".join(c if c.isprintable() else " " for c in text).split())
