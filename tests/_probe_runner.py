"""Parent side of the hostile-input probes: one long-lived worker process runs the probes, and a
probe that kills it (signal, abort) or stops answering within the time limit is recorded as a crash
or a hang and the worker is replaced. A crash therefore never takes pytest down, and a probe costs
milliseconds, not a Python start-up.
"""

from __future__ import annotations

import importlib.util
import math
import os
import pickle
import re
import select
import signal
import struct
import subprocess
import sys
import tempfile
import time
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np
from _probe_worker import (
    BAD_ERROR,
    CLEAN_ERROR,
    CRASH,
    FINITE,
    HANG,
    SILENT_WRONG,
    Attr,
    Call,
    entry_name,
)

HERE = Path(__file__).resolve().parent
#: Seconds a probe may take before it counts as a hang.
DEFAULT_TIME_LIMIT = float(os.environ.get("LIDAR_OVERLAP_PROBE_TIME_LIMIT", "20"))
#: A probe that waits this many times its limit in wall-clock time without using its CPU time is
#: blocked (a FIFO, a lock): generous, since on a loaded machine a probe gets a fraction of a core.
WALL_FACTOR = 10.0
#: How often the parent looks at the worker's CPU time while it waits.
POLL_SECONDS = 0.5
#: Seconds the worker may take to start and import the library.
START_LIMIT = 60.0
#: Table columns, in order.
VERDICTS = (CLEAN_ERROR, FINITE, BAD_ERROR, CRASH, HANG, SILENT_WRONG)
FAILURES = (BAD_ERROR, CRASH, HANG, SILENT_WRONG)


def _package_root() -> str:
    """The directory ``lidar_overlap`` is imported from here, found without importing it."""
    spec = importlib.util.find_spec("lidar_overlap")
    if spec is None or not spec.submodule_search_locations:
        raise RuntimeError("lidar_overlap is not importable (run with PYTHONPATH=python)")
    return str(Path(list(spec.submodule_search_locations)[0]).parent)


class _Worker:
    """One worker process, its stderr (a temporary file) and whether it has said it is ready."""

    def __init__(self) -> None:
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join([_package_root(), str(HERE), env.get("PYTHONPATH", "")])
        env.setdefault("OMP_NUM_THREADS", "2")
        self.stderr = tempfile.TemporaryFile()
        self.proc = subprocess.Popen(
            [sys.executable, "-c", "import _probe_worker; _probe_worker.serve()"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self.stderr,
            env=env,
            start_new_session=True,
        )
        self.ready = False

    def wait_ready(self) -> None:
        if not self.ready:
            if self.read_reply(START_LIMIT) != b"":
                raise RuntimeError(f"the probe worker did not start: {self.stderr_tail()}")
            self.ready = True

    def read_reply(self, limit: float):
        """The reply's payload; None when the worker has spent ``limit`` seconds of CPU time on it
        (a busy machine slows a probe, not its CPU time) or waited WALL_FACTOR x ``limit`` seconds
        without using it (blocked); raises EOFError if the worker died."""
        out = self.proc.stdout.fileno()
        start_cpu, start = _cpu_seconds(self.proc.pid), time.monotonic()
        header = b""
        while len(header) < 4:
            if not select.select([out], [], [], POLL_SECONDS)[0]:
                cpu = _cpu_seconds(self.proc.pid)
                if cpu is None or start_cpu is None:  # no CPU clock: the wall clock, generously
                    if time.monotonic() - start > WALL_FACTOR * limit:
                        return None
                elif cpu - start_cpu > limit or time.monotonic() - start > WALL_FACTOR * limit:
                    return None
                continue
            chunk = os.read(out, 4 - len(header))
            if not chunk:
                raise EOFError
            header += chunk
        (size,) = struct.unpack("<I", header)
        data = b""
        while len(data) < size:
            chunk = os.read(out, size - len(data))  # the reply follows its header at once
            if not chunk:
                raise EOFError
            data += chunk
        return data

    def stderr_tail(self, size: int = 800) -> str:
        self.stderr.seek(0, os.SEEK_END)
        self.stderr.seek(max(0, self.stderr.tell() - size))
        return self.stderr.read().decode(errors="replace").strip()

    def kill(self) -> None:
        try:
            os.killpg(
                self.proc.pid, signal.SIGKILL
            )  # the worker and any threads or children it made
        except ProcessLookupError:
            pass
        self.proc.wait()
        self.stderr.close()

    def close(self) -> None:
        try:
            self.proc.stdin.close()
            self.proc.wait(timeout=5)
            self.stderr.close()
        except (OSError, subprocess.TimeoutExpired):
            self.kill()


class ProbeRunner:
    """Runs probes (:class:`Call` trees) in a worker process; ``run`` returns the worker's
    judgement, or a crash or hang verdict with the worker's last stderr lines. A spare worker starts
    in the background as soon as one is in use, so that replacing a crashed or hung worker costs no
    start-up."""

    def __init__(self, time_limit: float = DEFAULT_TIME_LIMIT) -> None:
        self.time_limit = time_limit
        self._worker = None
        self._spare = None
        self.restarts = 0

    def _active(self) -> _Worker:
        if self._worker is None:
            self._worker, self._spare = (self._spare or _Worker()), None
            self._worker.wait_ready()
        if self._spare is None:
            self._spare = _Worker()
        return self._worker

    def _retire(self, outcome: dict) -> dict:
        self._worker = None
        self.restarts += 1
        return outcome

    def close(self) -> None:
        for worker in (self._worker, self._spare):
            if worker is not None:
                worker.close()
        self._worker = self._spare = None

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def run(self, probe: Call, time_limit: float | None = None) -> dict:
        """Run one probe; the outcome dict has ``verdict`` (one of VERDICTS), ``why`` and, by
        verdict, ``type``/``message`` (errors), ``summary`` (results) or ``signal``/``stderr``
        (crashes)."""
        limit = self.time_limit if time_limit is None else time_limit
        worker = self._active()
        request = pickle.dumps(probe)
        start = time.monotonic()
        try:
            worker.proc.stdin.write(struct.pack("<I", len(request)) + request)
            worker.proc.stdin.flush()
            data = worker.read_reply(limit)
        except (EOFError, BrokenPipeError):
            code = worker.proc.wait()
            stderr = worker.stderr_tail()
            worker.stderr.close()
            return self._retire(
                {
                    "verdict": CRASH,
                    "signal": -code if code < 0 else None,
                    "returncode": code,
                    "stderr": stderr,
                    "why": f"worker died ({_describe_exit(code)})",
                    "seconds": time.monotonic() - start,
                }
            )
        if data is None:
            stderr = worker.stderr_tail()
            worker.kill()
            return self._retire(
                {
                    "verdict": HANG,
                    "why": f"no answer within {limit:g} s of CPU time (or blocked)",
                    "seconds": limit,
                    "stderr": stderr,
                }
            )
        return pickle.loads(data)


def _cpu_seconds(pid: int):
    """CPU seconds (user + system, all threads) process ``pid`` has used; None where /proc cannot
    say (not Linux)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            fields = f.read().rsplit(b")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return None


def _describe_exit(code: int) -> str:
    if code < 0:
        try:
            return f"signal {signal.Signals(-code).name}"
        except ValueError:
            return f"signal {-code}"
    return f"exit status {code}"


# ---------------------------------------------------------------------------------------- reporting
def render(node) -> str:
    """The Python expression that reproduces a probe (``lo`` is lidar_overlap, ``np`` numpy)."""
    if isinstance(node, Call):
        fn = (
            f"{render(node.fn.node)}.{node.fn.name}"
            if isinstance(node.fn, Attr)
            else (node.fn if node.fn.startswith("np.") else f"lo.{node.fn}")
        )
        parts = [render(a) for a in node.args] + [
            f"{k}={render(v)}" for k, v in node.kwargs.items()
        ]
        return f"{fn}({', '.join(parts)})"
    if isinstance(node, float):
        if math.isnan(node):
            return "float('nan')"
        return (
            repr(float(node))
            if math.isfinite(node)
            else ("float('inf')" if node > 0 else "-float('inf')")
        )
    if isinstance(node, int) and not isinstance(node, bool) and abs(node) >= 10**20:
        exponent = len(str(abs(node))) - 1
        return ("-" if node < 0 else "") + (
            f"10**{exponent}" if abs(node) == 10**exponent else repr(node)
        )
    if isinstance(node, tuple):
        inner = ", ".join(render(v) for v in node)
        return f"({inner},)" if len(node) == 1 else f"({inner})"
    if isinstance(node, list):
        return f"[{', '.join(render(v) for v in node)}]"
    if isinstance(node, dict):
        return "{" + ", ".join(f"{render(k)}: {render(v)}" for k, v in node.items()) + "}"
    if isinstance(node, np.ndarray):
        return (
            f"np.array({node.tolist()!r}, dtype={node.dtype.name!r})"
            if node.size <= 8
            else f"<array shape {node.shape} {node.dtype}>"
        )
    return repr(node)


def describe(probe: Call, outcome: dict) -> str:
    """A broken probe: its reproducer, verdict and reason."""
    detail = outcome.get("why", "")
    if outcome["verdict"] == BAD_ERROR:
        detail = f"{outcome['type']}: {outcome['message'][:200]} ({detail})"
    if outcome["verdict"] == CRASH and outcome.get("stderr"):
        detail += f"; stderr: {outcome['stderr'].splitlines()[-1][:200]}"
    return f"{outcome['verdict'].upper()}: {render(probe)}\n    -> {detail}"


def cause(probe: Call, outcome: dict) -> tuple:
    """What a broken probe has in common with others that break the same way: entry point, verdict,
    and the error or the reason with its numbers blanked."""
    text = outcome.get("message") if outcome["verdict"] == BAD_ERROR else outcome.get("why", "")
    text = re.sub(r"\(np\.float64\(([^)]*)\)", r"(\1", text or "")
    return (
        entry_name(probe),
        outcome["verdict"],
        outcome.get("type", ""),
        re.sub(r"[-+]?\b\d[\d.e+-]*|nan|inf", "#", text.splitlines()[0] if text else "")[:100],
    )


class Tally:
    """Outcome counts per entry point, and the broken probes grouped by cause."""

    def __init__(self) -> None:
        self.counts = defaultdict(Counter)
        self.total = Counter()
        self.causes: dict = defaultdict(list)

    @property
    def broken(self) -> list:
        return [pair for group in self.causes.values() for pair in group]

    def add(self, probe: Call, outcome: dict) -> None:
        self.counts[entry_name(probe)][outcome["verdict"]] += 1
        self.total[outcome["verdict"]] += 1
        if outcome["verdict"] in FAILURES:
            self.causes[cause(probe, outcome)].append((probe, outcome))

    def table(self) -> str:
        head = (
            "entry point",
            "tried",
            "clean error",
            "finite result",
            "bad error",
            "crash",
            "hang",
            "silent wrong",
        )
        rows = [
            (name, sum(c.values()), *(c[v] for v in VERDICTS))
            for name, c in sorted(self.counts.items())
        ]
        rows.append(("TOTAL", sum(self.total.values()), *(self.total[v] for v in VERDICTS)))
        width = max(len(r[0]) for r in rows + [head])
        lines = [f"{head[0]:<{width}} " + " ".join(f"{h:>13}" for h in head[1:])]
        lines += [f"{r[0]:<{width}} " + " ".join(f"{v:>13}" for v in r[1:]) for r in rows]
        return "\n".join(lines)

    def report(self, limit: int = 40) -> str:
        """Each cause (most frequent first) with its count and its shortest reproducer."""
        groups = sorted(self.causes.values(), key=len, reverse=True)
        lines = []
        for group in groups[:limit]:
            probe, outcome = min(group, key=lambda pair: len(render(pair[0])))
            lines.append(
                f"[{len(group)} probe{'s' if len(group) > 1 else ''}] {describe(probe, outcome)}"
            )
        if len(groups) > limit:
            lines.append(f"... and {len(groups) - limit} more causes")
        return "\n".join(lines)


class Campaign:
    """Probes run through one runner and tallied. A build that hangs or crashes on many probes would
    make a campaign slow (a hang costs the whole time limit), so past ``max_hangs`` hangs or
    ``max_crashes`` crashes the remaining probes are only counted as not run; the campaign has
    failed by then anyway."""

    def __init__(self, runner: ProbeRunner, max_hangs: int = 2, max_crashes: int = 40) -> None:
        self.runner, self.max_hangs, self.max_crashes = runner, max_hangs, max_crashes
        self.tally = Tally()
        self.not_run = 0
        self.seconds = 0.0

    def run(self, probe: Call) -> None:
        if self.tally.total[HANG] >= self.max_hangs or self.tally.total[CRASH] >= self.max_crashes:
            self.not_run += 1
            return
        start = time.monotonic()
        self.tally.add(probe, self.runner.run(probe))
        self.seconds += time.monotonic() - start

    def failure_report(self) -> str:
        tried = sum(self.tally.total.values())
        head = (
            f"{len(self.tally.broken)} of {tried} probes broke the input contract, "
            f"{len(self.tally.causes)} causes"
        )
        if self.not_run:
            head += (
                f" ({self.not_run} more not run after {self.max_hangs} hangs or {self.max_crashes} "
                "crashes)"
            )
        return f"{head}:\n{self.tally.table()}\n\n{self.tally.report()}"
