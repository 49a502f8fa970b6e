#!/usr/bin/env python3
"""Regenerates docs/images/map_report.png, README's picture of the force-map report.

Fits the bundled 16 x 16 Bruker force volume of a polyacrylamide gel (../shared/data/instrument/
bruker/20200903_Egel2.0_00023.spm; Hertz, R = 20 nm as its header states) with
`layerjkr fit-map --report`, opens the report in headless Chromium (Selenium), selects one
pixel and saves the window as a PNG reduced to a 256-colour palette (PIL) to keep it small.

    tools/report_screenshot.py [--cli build/bin/layerjkr] [--out docs/images/map_report.png]
                               [--pixel 119] [--keep DIR]

Needs python3-selenium, chromium, chromium-driver and python3-pil (scripts/install-deps.sh).
"""
import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
VOLUME = ROOT.parent / "shared" / "data" / "instrument" / "bruker" / "20200903_Egel2.0_00023.spm"
SCENE = '{"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "half_space", "E": 1e4, "nu": 0.5}}'


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", default=str(ROOT / "build" / "bin" / "layerjkr"))
    ap.add_argument("--out", default=str(ROOT / "docs" / "images" / "map_report.png"))
    ap.add_argument("--pixel", type=int, default=119, help="the curve to show (0-based)")
    ap.add_argument("--keep", help="also keep the report directory here")
    args = ap.parse_args()
    if not VOLUME.exists():
        sys.exit("report_screenshot: %s is absent (the shared data beside the repository)" % VOLUME)
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    from PIL import Image

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        (tmp / "scene.json").write_text(SCENE)
        report = tmp / "report"
        # Short relative names: the page shows them.
        (tmp / VOLUME.name).symlink_to(VOLUME)
        subprocess.run([os.path.abspath(args.cli), "fit-map", VOLUME.name, "--scene", "scene.json", "--free", "E,delta0,P0",
                        "--jobs", "2", "--out", "results.csv", "--report", "report"], check=True, cwd=tmp)
        opts = Options()
        opts.binary_location = shutil.which("chromium") or shutil.which("chromium-browser")
        for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,1000",
                  "--force-device-scale-factor=1", "--hide-scrollbars"):
            opts.add_argument(a)
        driver = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=opts)
        try:
            driver.get((report / "index.html").as_uri())
            for _ in range(100):
                if driver.execute_script("return !!window.layerjkr"):
                    break
                time.sleep(0.1)
            driver.execute_script("window.layerjkr.select(arguments[0])", args.pixel)
            time.sleep(0.5)
            raw = tmp / "raw.png"
            driver.save_screenshot(str(raw))
        finally:
            driver.quit()
        image = Image.open(raw).convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
        image.save(args.out, optimize=True)
        if args.keep:
            shutil.copytree(report, args.keep, dirs_exist_ok=True)
    print("%s: %d bytes" % (args.out, pathlib.Path(args.out).stat().st_size))


if __name__ == "__main__":
    main()
