"""Headless Chromium for the view's tests: Debian's chromium driven through its chromedriver by
Selenium, nothing downloaded. Every wait is bounded; the browser and the served page stop when the
test ends."""

import contextlib
import os
import pathlib
import queue
import re
import shutil
import subprocess
import sys
import threading
import time

import pytest

CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
SETUP = (
    "sudo apt-get install -y chromium chromium-driver && .venv/bin/pip install selenium '.[app]' "
    "&& .venv/bin/python -m pytest tests/test_view_browser.py "
    "(make test installs both when run as root)"
)
#: Where the tests keep their screenshots and timings.
ARTIFACTS = pathlib.Path(__file__).resolve().parent.parent / "build" / "test-artifacts"
WAIT = 60.0  # s, the longest any page, server or browser step may take on a loaded machine
#: Table 1's scenario, served by the view and saved back by its twin (50 ranges, RT).
TABLE1_TOML = """name = "twin"
[beam]
wavelength = 355e-9
waist_radius = 1e-3
[telescope]
diameter = 0.15
focal_length = 1.0
obstruction_radius = 0.0
obstruction_distance = 0.7
[detector]
fov = 0.9e-3
[ranges]
start = 5.0
stop = 1000.0
count = 50
spacing = "log"
[run]
method = "rt"
tolerance = 1e-4
"""


def require_browser():
    """Skip, with the command that makes the test run, when chromium, its driver or selenium is
    missing."""
    pytest.importorskip("trame", reason=f"the view needs its extra; run: {SETUP}")
    pytest.importorskip("selenium", reason=f"needs selenium; run: {SETUP}")
    for path in (CHROMIUM, CHROMEDRIVER):
        if not (os.path.exists(path) or shutil.which(os.path.basename(path))):
            pytest.skip(f"{path} is missing; run: {SETUP}")


@contextlib.contextmanager
def chromium(width=1500, height=950):
    """A headless Chromium (WebGL by SwiftShader, as on a machine without a GPU)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    os.environ["SE_OFFLINE"] = "true"  # Selenium Manager must not look for drivers on the web
    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium") or CHROMIUM
    for arg in (
        "--headless=new",
        "--no-sandbox",
        f"--window-size={width},{height}",
        "--use-angle=swiftshader",
        "--enable-unsafe-swiftshader",
        "--disable-dev-shm-usage",
        "--no-first-run",
    ):
        options.add_argument(arg)
    driver = webdriver.Chrome(
        service=Service(executable_path=shutil.which("chromedriver") or CHROMEDRIVER),
        options=options,
    )
    try:
        driver.set_page_load_timeout(WAIT)
        driver.set_script_timeout(WAIT)
        yield driver
    finally:
        driver.quit()


def wait_for(condition, what: str, timeout: float = WAIT, poll: float = 0.05):
    """The first ``condition()`` that is not None, False or empty within ``timeout`` seconds, else a
    failure saying ``what``."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if (
            value is not None
            and value is not False
            and not (isinstance(value, (list, dict, str)) and not value)
        ):
            return value
        if time.monotonic() > deadline:
            pytest.fail(f"timed out after {timeout:g} s waiting for {what}")
        time.sleep(poll)


@contextlib.contextmanager
def served(args, cwd):
    """``lidar-overlap view ARGS --port 0 --no-browser --timeout`` in a subprocess; yields its URL
    and stops it at the end (it also stops by itself once no page has been connected for WAIT
    seconds)."""
    command = [
        sys.executable,
        "-m",
        "lidar_overlap.cli",
        "view",
        *map(str, args),
        "--port",
        "0",
        "--no-browser",
        "--timeout",
        str(int(WAIT)),
    ]
    process = subprocess.Popen(
        command,
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env={k: v for k, v in os.environ.items() if k != "DISPLAY"},
    )
    lines: "queue.Queue[str]" = queue.Queue()
    threading.Thread(
        target=lambda: [lines.put(line) for line in process.stdout], daemon=True
    ).start()
    output = []
    try:
        deadline = time.monotonic() + WAIT
        while True:
            try:
                line = lines.get(timeout=max(0.1, deadline - time.monotonic()))
            except queue.Empty:
                pytest.fail(f"the view printed no URL within {WAIT:g} s: {''.join(output)}")
            output.append(line)
            match = re.search(r"lidar-overlap view: (http://\S+)", line)
            if match:
                break
            if process.poll() is not None or time.monotonic() > deadline:
                pytest.fail(f"the view did not start: {''.join(output)}")
        yield match.group(1)
    finally:
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(timeout=10)


def pixels(png: bytes):
    """(h, w, 3) RGB values 0-255 of a PNG."""
    import io

    import matplotlib.image

    rgb = matplotlib.image.imread(io.BytesIO(png), format="png")[..., :3]
    return (rgb * 255 if rgb.dtype.kind == "f" else rgb).astype(float)


def drawn(rgb) -> float:
    """The fraction of pixels that differ from the picture's most common colour by more than 30
    levels."""
    import numpy as np

    flat = rgb.reshape(-1, 3)
    values, counts = np.unique(flat.astype(np.uint8), axis=0, return_counts=True)
    background = values[np.argmax(counts)]
    return float(np.mean(np.any(np.abs(flat - background) > 30, axis=1)))


def drawn_canvas(page, selector: str, what: str, share: float):
    """(the first canvas matching the CSS ``selector``, its RGB screenshot once more than ``share``
    of its pixels are drawn), each wait bounded and named by ``what``."""
    from selenium.webdriver.common.by import By

    canvas = wait_for(lambda: page.find_elements(By.CSS_SELECTOR, selector), what)[0]

    def picture():
        rgb = pixels(canvas.screenshot_as_png)
        return rgb if drawn(rgb) > share else None

    return canvas, wait_for(picture, "the scene to be drawn")
