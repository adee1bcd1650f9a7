"""The interactive view's page in headless Chromium: a slider moved with the keyboard must bring the
plotted G(z) to what lo.overlap gives for the moved system, and the scene must draw. Screenshots
and the measured slider-to-update time are kept in build/test-artifacts/ (the time is reported,
never asserted). The twin behind the page is tested on its own in test_view.py."""

import json
import time

import numpy as np
import pytest
from _browser import (
    ARTIFACTS,
    TABLE1_TOML,
    chromium,
    drawn,
    drawn_canvas,
    pixels,
    require_browser,
    served,
    wait_for,
)

import lidar_overlap as lo

pytest.importorskip("pyvista")
from lidar_overlap.io.scenario import load_scenario  # noqa: E402
from lidar_overlap.views.twin import sliders_for  # noqa: E402

SLIDER = "tilt_x"
MOVES = 5  # slider steps timed one by one
JS_CURVE = (
    "const p = document.querySelector('#curve .js-plotly-plot'); "
    "return p && p.data ? p.data[0].y : null;"
)
# Stamps (performance.now(), ms) of the key press, of the new figures' arrival (the slider's label
# changes in the same message), of the first frame that shows the new curve (plotly has taken the
# new data: Plotly.react draws 2-D plots synchronously) and of the scene's update counter changing
# (sent after the scene's moved coordinates, on the same socket).
JS_STAMPS = """window.__t = {};
const gd = document.querySelector('#curve .js-plotly-plot'), y0 = gd.data[0].y;
document.addEventListener('keydown', () => {
  window.__t.key = window.__t.key || performance.now();
}, true);
// the time the frame's callbacks run (a frame's own time stamp is when it began)
(function frame() {
  if (window.__t.key && !window.__t.curve && gd.data[0].y !== y0) {
    window.__t.curve = performance.now();
  }
  if (!window.__t.curve) requestAnimationFrame(frame);
})();
const stamp = (name, selector) => new MutationObserver(() => {
  if (window.__t.key && !window.__t[name]) window.__t[name] = performance.now(); }).observe(
  document.querySelector(selector), {childList: true, subtree: true, characterData: true});
stamp('data', '#label-tilt_x');          // the new figures and texts have arrived (one message)
stamp('scene', '#scene-version');"""


def test_page_slider_moves_curve_to_lo_overlap(tmp_path):
    require_browser()
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    (tmp_path / "twin.toml").write_text(TABLE1_TOML)
    scenario = load_scenario(tmp_path / "twin.toml")
    ranges = np.geomspace(5.0, 1000.0, 200)
    slider = sliders_for(scenario.system)[SLIDER]
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    with served(["twin.toml", "--out", tmp_path / "saved"], tmp_path) as url, chromium() as page:
        page.get(url)
        before = np.array(
            wait_for(lambda: page.execute_script(JS_CURVE), "the G(z) plot"), dtype=float
        )
        np.testing.assert_allclose(
            before, lo.overlap(scenario.system, ranges, "rt").overlap, rtol=0, atol=1e-12
        )
        thumb = page.find_element(By.CSS_SELECTOR, f"#slider-{SLIDER} .v-slider-thumb")
        start = int(thumb.get_attribute("aria-valuenow"))
        wait_for(
            lambda: page.execute_script("return document.querySelector('#scene canvas') !== null"),
            "the 3-D scene's canvas",
        )
        time.sleep(1.0)  # the first scene and figures settle
        runs = []
        for _ in range(MOVES):  # one key press at a time, each waited for
            page.execute_script(JS_STAMPS)
            thumb.send_keys(Keys.ARROW_RIGHT)
            runs.append(
                wait_for(
                    lambda: (lambda t: t if t and {"curve", "scene", "data"} <= set(t) else None)(
                        page.execute_script("return window.__t")
                    ),
                    "the update's time stamps",
                )
            )
            runs[-1]["server"] = page.find_element(
                By.CSS_SELECTOR, "#timing"
            ).text  # sent with the scene's counter
            time.sleep(0.3)
        position = start + MOVES
        after = np.array(page.execute_script(JS_CURVE), dtype=float)
        assert int(thumb.get_attribute("aria-valuenow")) == position
        moved = lo.parameters.replace(scenario.system, {"beam.tilt[0]": slider.value(position)})
        expected = lo.overlap(moved, ranges, "rt", tolerance=1e-4).overlap
        np.testing.assert_allclose(after, expected, rtol=0, atol=1e-12)
        assert np.max(np.abs(after - before)) > 1e-6
        time.sleep(0.5)  # vtk.js draws the moved scene on its next frame
        page.save_screenshot(str(ARTIFACTS / "view.png"))
        scene = pixels(page.find_element(By.CSS_SELECTOR, "#scene").screenshot_as_png)
        assert drawn(scene) > 0.01  # the beam and FOV cones are drawn
        page.find_element(By.CSS_SELECTOR, "#save").click()
        wait_for(lambda: (tmp_path / "saved" / "twin.toml").exists(), "the saved scenario")
        assert load_scenario(tmp_path / "saved" / "twin.toml").system == moved
    timing = {
        f"key_to_{name}_ms": [round(t[name] - t["key"], 1) for t in runs]
        for name in ("data", "curve", "scene")
    }
    timing.update(
        {
            f"median_key_to_{name}_ms": float(np.median(timing[f"key_to_{name}_ms"]))
            for name in ("data", "curve", "scene")
        }
    )
    timing["server"] = [t["server"] for t in runs]
    (ARTIFACTS / "view_timing.json").write_text(json.dumps(timing, indent=1))
    print(f"slider to updated curve and scene: {timing}")


def test_html_scene_draws_in_the_browser(tmp_path):
    require_browser()
    path = lo.save_scene(
        lo.paper_table1(obstruction_radius=0.02),
        tmp_path / "scene.html",
        planes=(100.0,),
        color_by="overlap",
    )
    text = path.read_text(encoding="utf-8")
    assert "kitware.github.io/vtk-js/icon" not in text and "<script" in text
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    with chromium(1000, 700) as page:
        page.get(path.as_uri())
        canvas, rgb = drawn_canvas(page, "canvas", "the vtk.js canvas", 0.01)
        page.save_screenshot(str(ARTIFACTS / "scene_html.png"))
        errors = [e for e in page.get_log("browser") if e["level"] == "SEVERE"]
    assert rgb.shape[0] > 100 and len(np.unique(rgb.reshape(-1, 3), axis=0)) > 50
    assert errors == []  # nothing failed to load: no network needed
