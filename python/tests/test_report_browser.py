"""The force-map report in a real browser (headless Chromium through Selenium): fit-map --report
on a generated 8 x 8 QI map plus a broken file and a CSV curve, then the page's
window.layerjkr.select against the CSV, a click on a pixel, the arrow keys, the status
filter, the console (no errors) and the network (no request leaves file://, and the page
works offline). Skipped visibly without selenium, chromium and chromedriver (installed by
scripts/install-deps.sh) or without ../shared (the map's source curves)."""
import csv
import json
import os
import pathlib
import shutil
import subprocess
import time

import pytest

from conftest import CLI, SHARED, SOURCE

webdriver = pytest.importorskip("selenium.webdriver", reason="python3-selenium is not installed")
from selenium.webdriver.common.action_chains import ActionChains  # noqa: E402
from selenium.webdriver.common.actions.action_builder import ActionBuilder  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402

BUILD = pathlib.Path(os.environ.get("LAYERJKR_BUILD_DIR", SOURCE / "build"))
MAKE_MAP = os.environ.get("LAYERJKR_MAKE_MAP", str(BUILD / "bin" / "make_instrument_map"))
# Markup in a file name is shown as text, never interpreted.
BROKEN = "<b>broken<i> &amp;.jpk-force"
FLAT = "flat.csv"
SCENE = '{"indenter": {"shape": "paraboloid", "R": 4e-8}, "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}}'


def _browser_paths():
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver = shutil.which("chromedriver")
    if not chromium or not driver:
        pytest.skip("chromium and chromedriver are not installed (scripts/install-deps.sh installs them)")
    return chromium, driver


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """fit-map --report of an 8 x 8 QI map, a broken file and a CSV curve (66 items: a grid view
    and a view by index); without ../shared, of 8 copies of the bundled curve and a broken file
    (9 items, by index). Returns the directory, the page, the table's rows and whether a grid
    view is there."""
    if not os.path.exists(CLI):
        pytest.skip("the layerjkr CLI is not built at %s" % CLI)
    d = tmp_path_factory.mktemp("report")
    (d / BROKEN).write_text("not a zip")
    # Readable but not fittable: a flat curve, no contact anywhere. Its pixel shows its samples.
    (d / FLAT).write_text("delta,P\n" + "".join("%g,%g\n" % (1e-8 * k, 1e-12 * ((k * 7919) % 13 - 6))
                                                   for k in range(60)))
    source = SHARED / "data" / "instrument"
    real = SHARED / "data" / "real" / "jpk_spot3_0192_approach.csv"
    if source.is_dir() and real.exists() and os.path.exists(MAKE_MAP):
        subprocess.run([MAKE_MAP, "qi", "8", str(d / "map8.jpk-qi-data"), "--source", str(source)], check=True,
                       capture_output=True)
        (d / "hertz.json").write_text(SCENE)
        inputs = [str(d / "map8.jpk-qi-data"), str(d / BROKEN), str(real), str(d / FLAT)]
        flags = ["--scene", str(d / "hertz.json"), "--free", "E,delta0,P0"]
        grid = True
    else:
        # Still a browser test, of the view by index: the map needs ../shared and make_instrument_map.
        print("LAYERJKR_NOTE: ../shared or make_instrument_map absent: the report of CSV curves only (no grid view)")
        inputs = []
        for k in range(8):
            shutil.copy(SOURCE / "data" / "curves" / "hydrogel_film_two_term.csv", d / ("c%d.csv" % k))
            inputs.append(str(d / ("c%d.csv" % k)))
        inputs.append(str(d / BROKEN))
        inputs.append(str(d / FLAT))
        flags = ["--scene", str(SOURCE / "data" / "scenes" / "hydrogel_film_two_term.json"), "--branch", "all",
                 "--free", "E,w,delta0,P0"]
        grid = False
    r = subprocess.run([CLI, "fit-map"] + inputs + flags + ["--jobs", "2", "--out", str(d / "res.csv"),
                                                            "--report", str(d / "rep")], capture_output=True, text=True)
    assert r.returncode == 3, r.stderr  # the broken input failed, the others fitted
    with open(d / "res.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return d, d / "rep" / "index.html", rows, grid


@pytest.fixture(scope="module")
def browser():
    chromium, driver_path = _browser_paths()
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    opts = Options()
    opts.binary_location = chromium
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1500,1100",
              "--force-device-scale-factor=1"):
        opts.add_argument(a)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    driver = webdriver.Chrome(service=Service(driver_path), options=opts)
    yield driver
    driver.quit()


def _open(browser, page):
    browser.get(page.as_uri())
    for _ in range(100):
        if browser.execute_script("return !!(window.layerjkr && window.layerjkr.select)"):
            return
        time.sleep(0.1)
    raise AssertionError("window.layerjkr never appeared: " + json.dumps(browser.get_log("browser")))


def _same(csv_cell, value, column):
    """A CSV cell against the page's value: empty <-> null, numbers exactly, text exactly."""
    if column in ("file", "status", "error", "model", "identifiability", "quality"):
        return (csv_cell or None) == (value or None)
    if column in ("warnings", "notices"):  # the table joins a list in one cell
        return csv_cell == " | ".join(value or [])
    if csv_cell == "":
        return value is None
    return value is not None and float(csv_cell) == float(value)


def test_select_returns_the_csv_values_and_the_page_stays_offline(report, browser, tmp_path):
    _, page, rows, grid = report
    _open(browser, page)
    n = browser.execute_script("return window.layerjkr.data.count")
    assert n == len(rows) == (67 if grid else 10)
    assert {r["status"] for r in rows} == {"ok", "error"}  # both kinds are checked below
    for i in range(n):
        got = browser.execute_script("return window.layerjkr.select(arguments[0])", i)
        assert got["index"] == i
        for column, cell in rows[i].items():
            assert _same(cell, got[column], column), (i, column, cell, got[column])
        assert got["quality"] in ("ok", "warning", "not identifiable", "not converged", "failed")
        assert (got["quality"] == "failed") == (rows[i]["status"] == "error")
    # The values table shows the selected curve: a fitted one its E, a failed one its error.
    ok = next(i for i, r in enumerate(rows) if r["status"] == "ok")
    browser.execute_script("window.layerjkr.select(arguments[0])", ok)
    table = browser.find_element(By.ID, "values").text
    assert "E" in table and "\u00b1" in table
    bad = next(i for i, r in enumerate(rows) if r["status"] == "error")
    browser.execute_script("window.layerjkr.select(arguments[0])", bad)
    assert rows[bad]["error"][:40] in browser.find_element(By.ID, "values").text
    broken = next(i for i, r in enumerate(rows) if r["file"].endswith(BROKEN))
    browser.execute_script("window.layerjkr.select(arguments[0])", broken)
    assert BROKEN in browser.execute_script("return document.querySelector('#curve .gtitle').textContent")
    assert BROKEN in browser.find_element(By.ID, "values").text
    # A curve that was read but not fitted shows its samples as read, and why it failed.
    flat = next(i for i, r in enumerate(rows) if r["file"].endswith(FLAT))
    assert rows[flat]["status"] == "error" and rows[flat]["quality"] == "failed"
    browser.execute_script("window.layerjkr.select(arguments[0])", flat)
    traces = browser.execute_script("return document.getElementById('curve').data.map(t => [t.name, t.x.length])")
    assert traces == [["data (not fitted)", 60]]
    notes = browser.execute_script("return document.querySelectorAll('#curve .annotation-text')[0].textContent")
    assert notes.startswith("not fitted: ") and rows[flat]["error"][:30] in notes
    # A fitted curve: force against indentation in prefixed units, the fit as a line.
    browser.execute_script("window.layerjkr.select(arguments[0])", ok)
    curve = browser.execute_script("return document.getElementById('curve').data.map(t => [t.name, t.mode])")
    assert ["fit", "lines"] in curve
    xtitle = browser.execute_script("return document.querySelector('#curve .xtitle').textContent")
    assert xtitle.startswith("indentation") and ("[\u00b5m]" in xtitle or "[nm]" in xtitle), xtitle
    # A bad index is an error, not a silent no-op.
    with pytest.raises(Exception, match="not in 0 .. %d" % (n - 1)):
        browser.execute_script("return window.layerjkr.select(arguments[0])", n)
    # Layout: a map's curves at their pixels, everything else in the view by index, in order.
    views = browser.execute_script("return window.layerjkr.data.views")
    for i, r in enumerate(rows):
        if r["grid_x"]:
            v = views[0]
            assert v["kind"] == "grid" and v["cells"][int(r["grid_y"]) * v["nx"] + int(r["grid_x"])] == i
    rest = [i for i, r in enumerate(rows) if not r["grid_x"]]
    assert views[-1]["kind"] == "index" and [c for c in views[-1]["cells"] if c >= 0] == rest
    assert browser.execute_script("window.layerjkr.select(arguments[0]); return window.layerjkr.state().view",
                                  rest[0]) == len(views) - 1
    severe = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    # The one expected error: select(n) above threw on purpose.
    assert all("not in 0 .. %d" % (n - 1) in e["message"] for e in severe), severe
    urls = []
    for entry in browser.get_log("performance"):
        message = json.loads(entry["message"])["message"]
        if message["method"] == "Network.requestWillBeSent":
            urls.append(message["params"]["request"]["url"])
    assert urls and all(u.startswith(("file://", "data:", "blob:")) for u in urls), urls
    browser.save_screenshot(str(tmp_path / "report.png"))
    assert (tmp_path / "report.png").stat().st_size > 10000


def _selected(browser):
    return browser.execute_script("return window.layerjkr.state().selected")


def test_offline_click_arrow_keys_and_status_filter(report, browser, tmp_path):
    _, page, rows, grid = report
    browser.set_network_conditions(offline=True, latency=0, download_throughput=0, upload_throughput=0)
    browser.get_log("browser")  # drop earlier messages
    _open(browser, page)
    v = browser.execute_script("return window.layerjkr.data.views[0]")
    nx, ny, cells = v["nx"], v["ny"], v["cells"]
    in_view = [i for i in cells if i >= 0]
    state = browser.execute_script("return window.layerjkr.state()")
    assert state["selected"] == in_view[0] and state["view"] == 0 and state["shown"] == len(in_view)
    # A click on the pixel at (1, 1).
    target = cells[1 * nx + 1]
    assert target >= 0
    if grid:
        assert (rows[target]["grid_x"], rows[target]["grid_y"]) == ("1", "1")
    pos = browser.execute_script("return window.layerjkr.pixelPosition(arguments[0])", target)
    actions = ActionBuilder(browser)
    actions.pointer_action.move_to_location(int(pos["x"]), int(pos["y"])).click()
    actions.perform()
    for _ in range(50):
        if _selected(browser) == target:
            break
        time.sleep(0.1)
    assert _selected(browser) == target
    # Arrow keys move across the view as drawn: right to (2, 1), up to (2, 2) on a map (its y
    # grows upwards) or (2, 0) by index (rows go down), left, and down back.
    up = 1 if grid else -1
    path = [(Keys.ARROW_RIGHT, 2, 1), (Keys.ARROW_UP, 2, 1 + up), (Keys.ARROW_LEFT, 1, 1 + up), (Keys.ARROW_DOWN, 1, 1)]
    for key, x, y in path:
        ActionChains(browser).send_keys(key).perform()
        assert _selected(browser) == cells[y * nx + x], key
    # The status boxes toggle the markers over the map; every pixel keeps its value.
    qualities = browser.execute_script("return window.layerjkr.data.columns.quality")
    E = browser.execute_script("return window.layerjkr.data.columns.E")

    def drawn():
        z = browser.execute_script("return document.getElementById('map').data[0].z")
        return {(x, y) for y, zr in enumerate(z) for x, val in enumerate(zr) if val is not None}
    with_value = {(k % nx, k // nx) for k, i in enumerate(cells) if i >= 0 and E[i] is not None}
    assert drawn() == with_value
    assert browser.find_elements(By.ID, "show-ok") == []  # ok pixels carry no marker to toggle

    def markers():  # the status markers drawn over the map, by trace name
        return browser.execute_script(
            "return document.getElementById('map').data.slice(1, -1).map(t => [t.name, t.x.length])")
    counts = {q: sum(1 for i in in_view if qualities[i] == q) for q in ("warning", "not identifiable", "not converged",
                                                                         "failed")}
    assert markers() == [["%s (%d)" % (q, n), n] for q, n in counts.items() if n]
    for q in [q for q, n in counts.items() if n]:
        box = browser.find_element(By.ID, "show-" + q.replace(" ", "-"))
        box.click()
        assert markers() == [["%s (%d)" % (p, n), n] for p, n in counts.items() if n and p != q]
        assert drawn() == with_value, q  # unmarking a status hides no value
        assert browser.execute_script("return window.layerjkr.state().shown") == len(in_view)
        box.click()
    assert markers() == [["%s (%d)" % (q, n), n] for q, n in counts.items() if n]
    # Another field and the status map draw without errors.
    browser.execute_script("""
        var s = document.getElementById('field');
        s.value = '__quality'; s.dispatchEvent(new Event('change'));
        s.value = 'rms_residual'; s.dispatchEvent(new Event('change'));""")
    assert [e for e in browser.get_log("browser") if e["level"] in ("SEVERE", "WARNING")] == []
    browser.save_screenshot(str(tmp_path / "report_offline.png"))


def test_a_report_of_no_curves_opens_without_errors(browser, tmp_path):
    import layerjkr
    assert layerjkr.fit_batch([], str(SOURCE / "data" / "scenes" / "hydrogel_film_two_term.json"),
                              report=tmp_path / "rep") == []
    browser.set_network_conditions(offline=False, latency=0, download_throughput=-1, upload_throughput=-1)
    browser.get_log("browser")
    _open(browser, tmp_path / "rep" / "index.html")
    assert browser.find_element(By.ID, "summary").text == "No curves."
    assert [e for e in browser.get_log("browser") if e["level"] == "SEVERE"] == []
