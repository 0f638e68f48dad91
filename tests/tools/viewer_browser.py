#!/usr/bin/env python3
"""Pages written by massspring-simulate --html, loaded in a real browser (headless Chromium driven
by Selenium): run by ctest as

    viewer_browser.py MASSSPRING_SIMULATE SOURCE_DIR WORK_DIR [SCREENSHOT_DIR]

For a cloth with colliders (examples/scenes/drape.json), a FOSSSim 2D scene
(examples/scenes_xml/cantilever.xml), a chain without faces (examples/scenes/chain.json), and the
chain's page written from its CSV by scripts/viewer_page.py:
- the page is opened from its file (file://, nothing beside it) and draws without an error in the
  browser's console;
- the screenshot is not blank (the background and at least two other colours), and where a face
  (or a spring) of the cloth is on screen its colour map's colour is there (the same hue: the
  lighting only scales it);
- Play advances the frames;
- pressing End on the frame slider shows the last frame: its label says the last frame's time in
  seconds and the screenshot differs from the first frame's.
Screenshots are kept in WORK_DIR (and SCREENSHOT_DIR when given) as viewer-<scene>.png.
Skipped (exit 77) with the reason when Chromium, chromedriver, Selenium or Pillow is missing
(Debian: chromium, chromium-driver, python3-selenium, python3-pil; scripts/setup.sh installs
them)."""

import io
import os
import shutil
import subprocess
import sys
import time

from checks import check, fail, skip

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage",
                 "--window-size=900,700", "--hide-scrollbars", "--force-device-scale-factor=1",
                 # WebGL without a GPU: ANGLE on SwiftShader (software)
                 "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                 "--ignore-gpu-blocklist"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)


BACKGROUND = (244, 244, 244)


def has_colour(pixel, rgb):
    """True when `pixel` is `rgb` lit (s x rgb, 0.4 <= s <= 1.2: the lighting scales a colour) or
    `rgb` drawn over the background with coverage a >= 0.3 (an antialiased line's edge)."""
    lit = [p / c for p, c in zip(pixel, rgb) if c >= 30]
    if lit and all(0.4 <= s <= 1.2 for s in lit) and max(lit) - min(lit) <= 0.08:
        return True
    useful = [(p - b) / (c - b) for p, c, b in zip(pixel, rgb, BACKGROUND) if abs(c - b) >= 30]
    if not useful:
        return False
    a = sum(useful) / len(useful)
    return a >= 0.3 and all(abs(a * c + (1 - a) * b - p) <= 10
                            for p, c, b in zip(pixel, rgb, BACKGROUND))


def shows_colour(image, x, y, rgb, radius=4):
    """True when a pixel within `radius` of (x, y) that is not the background has `rgb`."""
    width, height = image.size
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            px, py = int(round(x)) + dx, int(round(y)) + dy
            if not (0 <= px < width and 0 <= py < height):
                continue
            got = image.getpixel((px, py))[:3]
            if got != BACKGROUND and has_colour(got, rgb):
                return True
    return False


def screenshot(driver):
    from PIL import Image
    return Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert("RGB")


def look(driver, page, name, keep):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys
    driver.get("file://" + page)
    deadline = time.time() + 60
    while time.time() < deadline:
        state = driver.execute_script(
            "return [window.massspringViewer ? true : false, "
            "document.getElementById('message').textContent]")
        if state[0] or state[1]:
            break
        time.sleep(0.1)
    check(state[0], f"{name}: the viewer did not start: {state[1]!r}; console: "
                    f"{driver.get_log('browser')}")
    v = "window.massspringViewer"
    first = screenshot(driver)
    colours = first.getcolors(maxcolors=1 << 20)
    check(colours is not None and len(colours) >= 3 and
          max(colours)[0] < 0.95 * first.size[0] * first.size[1],
          f"{name}: the screenshot is blank")

    # Where the cloth is, its colour: the middle face (or spring) at frame 0.
    faces = driver.execute_script(f"return {v}.faces")
    if faces:
        f = faces // 2
        corners = driver.execute_script(f"return {v}.faceCorners({f})")
        points = [driver.execute_script(f"return {v}.position({i})") for i in corners]
        strain = driver.execute_script(f"return {v}.faceStrain({f})")
        what = f"face {f}"
    else:
        e = driver.execute_script(f"return {v}.springs") // 2
        points = [driver.execute_script(f"return {v}.position({i})")
                  for i in driver.execute_script(f"return {v}.spring({e})")]
        strain = driver.execute_script(f"return {v}.springStrain({e})")
        what = f"spring {e}"
    centre = [sum(p[c] for p in points) / len(points) for c in range(3)]
    x, y = driver.execute_script(f"return {v}.screenOf(arguments[0], arguments[1], arguments[2])",
                                 *centre)
    rgb = driver.execute_script(f"return {v}.colourOfStrain(arguments[0])", strain)
    check(0 <= x < first.size[0] and 0 <= y < first.size[1],
          f"{name}: {what} is off screen at ({x:.0f}, {y:.0f})")
    check(shows_colour(first, x, y, rgb),
          f"{name}: no pixel near ({x:.0f}, {y:.0f}), where {what} is, has its colour {rgb} "
          f"(strain {strain:.3g}); there: {first.getpixel((int(x), int(y)))}")

    # Play advances the frames (in real time), and stops at the last.
    driver.find_element(By.ID, "play").click()
    deadline = time.time() + 20
    while time.time() < deadline and driver.execute_script(f"return {v}.frame()") == 0:
        time.sleep(0.05)
    check(driver.execute_script(f"return {v}.frame()") > 0, f"{name}: Play shows no other frame")
    if driver.find_element(By.ID, "play").text == "Pause":
        driver.find_element(By.ID, "play").click()

    # The slider: End shows the last frame, and the picture changes.
    slider = driver.find_element(By.ID, "slider")
    slider.send_keys(Keys.END)
    frames = driver.execute_script(f"return {v}.frames")
    check(driver.execute_script(f"return {v}.frame()") == frames - 1,
          f"{name}: End on the slider did not show the last frame")
    label = driver.find_element(By.ID, "time").text
    check(label.startswith("t = ") and " s" in label, f"{name}: time label {label!r}")
    last = screenshot(driver)
    changed = sum(1 for a, b in zip(first.getdata(), last.getdata()) if a != b)
    check(changed > 200, f"{name}: the first and the last frame differ in {changed} pixels only")
    errors = [entry for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
    check(not errors, f"{name}: errors in the console: {errors}")
    for folder in keep:
        first.save(os.path.join(folder, f"viewer-{name}.png"))
        last.save(os.path.join(folder, f"viewer-{name}-last.png"))
    return changed, label


def main():
    simulate, source, work = sys.argv[1:4]
    keep = [work] + sys.argv[4:5]
    simulate = os.path.abspath(simulate)
    for program, package in ((CHROMIUM, "chromium"), (CHROMEDRIVER, "chromium-driver")):
        if not os.access(program, os.X_OK):
            skip(f"{program} missing (Debian's {package}; scripts/setup.sh installs it)")
    try:
        import selenium  # noqa: F401
        from PIL import Image  # noqa: F401
    except ImportError as error:
        skip(f"{error} (Debian: python3-selenium, python3-pil; scripts/setup.sh installs them)")

    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    runs = {
        "drape": [os.path.join(source, "examples", "scenes", "drape.json"), "--duration", "0.4",
                  "--every", "8"],
        "cantilever": [os.path.join(source, "examples", "scenes_xml", "cantilever.xml"),
                       "--steps", "600", "--every", "60"],
        "chain": [os.path.join(source, "examples", "scenes", "chain.json"), "--steps", "40",
                  "--every", "4"],
    }
    pages = {}
    for name, args in runs.items():
        page = os.path.join(work, name + ".html")
        result = subprocess.run([simulate] + args + ["--html", page, "--csv", page + ".csv",
                                                     "--quiet"],
                                capture_output=True, text=True, timeout=300)
        check(result.returncode == 0, f"{name}: exit {result.returncode}: {result.stderr}")
        pages[name] = page
    # The same page written from Python (scripts/viewer_page.py) from the chain's CSV.
    sys.path.insert(0, os.path.join(source, "scripts"))
    import viewer_page
    frames = {}
    with open(pages["chain"] + ".csv") as handle:
        next(handle)
        for line in handle:
            row = line.split(",")
            frames.setdefault(int(row[0]), []).append([float(v) for v in row[2:5]])
    springs, _ = viewer_page.read_obj(os.path.join(source, "examples", "scenes", "chain.obj"))
    pages["chain-python"] = os.path.join(work, "chain-python.html")
    viewer_page.write_page(pages["chain-python"], [frames[f] for f in sorted(frames)],
                           [f / 30 for f in sorted(frames)], springs, frames=sorted(frames))

    driver = browser()
    try:
        for name, page in pages.items():
            changed, label = look(driver, page, name, keep)
            print(f"{name}: {os.path.getsize(page)} bytes; drawn with the colour map's colour "
                  f"where the cloth is; last frame ({label}) differs in {changed} pixels")
    finally:
        driver.quit()
    print(f"OK: {len(pages)} pages drawn in Chromium, the slider moves the cloth, no console error")


if __name__ == "__main__":
    main()
