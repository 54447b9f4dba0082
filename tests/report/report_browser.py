"""`pierce report` in a real browser: headless Chromium, WebGL on SwiftShader.

For the STEP part with pocket floors and for the four-block assembly, the report is opened twice,
as it is and with #finding=2 in its address, and each time the page's DOM and a screenshot are
taken. Checked: no uncaught script error (<html data-errors>), the page built (data-ready), the
findings tables list every finding with its value, the 3D view is drawn in colour (its pixels in
the screenshot), #finding=2 selects finding 2 (data-selected, the row marked) and moves the camera
(the view's pixels change), and neither the file nor the loaded page references anything outside
the file.

    report_browser.py --pierce PIERCE --make-models MAKE_MODELS --chromium CHROMIUM [--screenshots DIR]

--screenshots DIR also opens each report as docs/REPORT.md shows it (the part with finding 2
selected, the assembly's clearance / clash map with its clash selected), checks it as above and
keeps the screenshots as DIR/report_cad_part.png and DIR/report_assembly.png.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from matplotlib import image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_models import network_references, report_data, write_blocks  # noqa: E402

WIDTH, HEIGHT = 1280, 900
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL: " + what, file=sys.stderr)


def open_in_chromium(chromium, html, fragment, png, profile):
    """The DOM after the page ran (and settled: virtual time) and a screenshot of it."""
    url = "file://" + html + fragment
    cmd = [chromium, "--headless", "--no-sandbox", "--use-gl=swiftshader", "--enable-unsafe-swiftshader",
           "--hide-scrollbars", "--user-data-dir=" + profile, "--window-size=%d,%d" % (WIDTH, HEIGHT),
           "--virtual-time-budget=15000", "--screenshot=" + png, "--dump-dom", url]
    run = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120, check=False)
    if run.returncode != 0 or not os.path.exists(png):
        raise RuntimeError("chromium failed (%d): %s" % (run.returncode, run.stderr.decode()[-2000:]))
    return run.stdout.decode("utf-8")


def view_pixels(dom, png):
    """The screenshot's pixels inside the 3D view (RGB floats in [0, 1])."""
    m = re.search(r'data-view-rect="(\d+),(\d+),(\d+),(\d+)"', dom)
    if not m:
        raise RuntimeError("the page did not say where its view is (no data-view-rect)")
    x, y, w, h = map(int, m.groups())
    pixels = image.imread(png)[..., :3]
    return pixels[y + 2:y + h - 2, x + 2:x + w - 2]


def coloured_share(pixels):
    """The share of pixels with a clear hue (neither white, grey nor black)."""
    return float(np.mean(pixels.max(axis=2) - pixels.min(axis=2) > 0.25))


def attribute(dom, name):
    """Attribute `name` of the page's <html> element (the first tag of the dump), or None."""
    start = dom.index("<html")
    m = re.search(r"\s%s=\"([^\"]*)\"" % name, dom[start:dom.index(">", start)])
    return m.group(1) if m else None


def finding_rows(dom):
    """{finding number: the row's cell texts} of the findings tables."""
    rows = {}
    for m in re.finditer(r'<tr class="finding( selected)?" data-finding="(\d+)">(.*?)</tr>', dom, re.S):
        rows[int(m.group(2))] = (bool(m.group(1)), re.findall(r"<td[^>]*>(.*?)</td>", m.group(3)))
    return rows


def check_report(name, html, args, work, expected_rows):
    """Opens report `html` twice (plain, #finding=2) and checks both."""
    with open(html, encoding="utf-8") as f:
        text = f.read()
    data = report_data(text)
    check(not network_references(text), "%s: the file references %s" % (name, network_references(text)[:3]))
    shots = {}
    for fragment in ("", "#finding=2"):
        png = os.path.join(work, "%s%s.png" % (name, "_finding2" if fragment else ""))
        dom = open_in_chromium(args.chromium, html, fragment, png, os.path.join(work, "profile"))
        label = name + (" " + fragment if fragment else "")
        check(attribute(dom, "data-errors") == "0", "%s: script errors: %s (%s)" % (
            label, attribute(dom, "data-errors"), re.findall(r'id="script-errors">(.*?)</pre>', dom, re.S)))
        check(attribute(dom, "data-ready") == "1", label + ": the page did not finish building")
        check(not network_references(dom), "%s: the loaded page references %s" % (label, network_references(dom)[:3]))
        rows = finding_rows(dom)
        check(sorted(rows) == [f["n"] for f in data["findings"]], "%s: finding rows %s, the data has %d findings" % (
            label, sorted(rows), len(data["findings"])))
        for n, cells in expected_rows.items():
            got = rows.get(n, (False, []))[1]
            check(all(any(re.fullmatch(c, g) for g in got) for c in cells),
                  "%s: row %d reads %s, expected cells matching %s" % (label, n, got, cells))
        pixels = view_pixels(dom, png)
        share = coloured_share(pixels)
        check(share > 0.05, "%s: the 3D view is blank or grey (%.3f of its pixels coloured)" % (label, share))
        if fragment:
            check(attribute(dom, "data-selected") == "2", label + ": finding 2 not selected (data-selected %s)" %
                  attribute(dom, "data-selected"))
            check(rows.get(2, (False,))[0] and not any(sel for n, (sel, _) in rows.items() if n != 2),
                  label + ": the row of finding 2 is not the one marked")
        else:
            check(attribute(dom, "data-selected") is None, label + ": a finding is selected without being asked for")
        shots[fragment] = pixels
    a, b = shots[""], shots["#finding=2"]
    moved = a.shape != b.shape or float(np.mean(np.abs(a - b).max(axis=2) > 0.1)) > 0.05
    check(moved, name + ": the view with #finding=2 looks like the default one (the camera did not move)")
    print("%s: %d findings, view %.0f%% coloured" % (name, len(data["findings"]), 100 * coloured_share(a)))


def screenshot_for_docs(name, html, fragment, selected, args, work):
    """Opens report `html` at `fragment`, checks it built with finding `selected` chosen, and
    returns its screenshot."""
    png = os.path.join(work, name + "_docs.png")
    dom = open_in_chromium(args.chromium, html, fragment, png, os.path.join(work, "profile"))
    check(attribute(dom, "data-errors") == "0" and attribute(dom, "data-selected") == str(selected),
          "%s %s: script errors or finding %d not selected" % (name, fragment, selected))
    check(coloured_share(view_pixels(dom, png)) > 0.05, "%s %s: the 3D view is blank" % (name, fragment))
    return png


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pierce", required=True)
    parser.add_argument("--make-models", required=True)
    parser.add_argument("--chromium", required=True)
    parser.add_argument("--screenshots", help="keep the default views here")
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="pierce_report.")
    try:
        subprocess.run([args.make_models, os.path.join(work, "models")], check=True, stdout=subprocess.DEVNULL)
        write_blocks(os.path.join(work, "blocks.obj"))
        part, assembly = os.path.join(work, "pocket_part.html"), os.path.join(work, "assembly.html")
        subprocess.run([args.pierce, "report", os.path.join(work, "models", "pocket_part.step"), "--per", "face",
                        "--min", "1", "-o", part], check=True, stdout=subprocess.DEVNULL)
        subprocess.run([args.pierce, "report", os.path.join(work, "blocks.obj"), "--per", "face", "--min", "1.2",
                        "--clearance", "0.5", "-o", assembly], check=True, stdout=subprocess.DEVNULL)
        # The thin walls with their minimum thickness; the pairs with their kind and gap or depth.
        check_report("cad_part", part, args, work, {1: ["pocket_part", r"0\.6"], 2: ["pocket_part", r"0\.8"]})
        check_report("assembly", assembly, args, work, {4: ["clash", "c", "d", r"0\.50?\d*"],
                                                        5: ["contact", "a", "b", "0"],
                                                        6: ["clearance", "b", "c", r"0\.3"]})
        if args.screenshots:
            shots = {"cad_part": screenshot_for_docs("cad_part", part, "#finding=2", 2, args, work),
                     "assembly": screenshot_for_docs("assembly", assembly, "#map=pairs&finding=4", 4, args, work)}
            if not failures:
                os.makedirs(args.screenshots, exist_ok=True)
                for name, png in shots.items():
                    shutil.copy(png, os.path.join(args.screenshots, "report_%s.png" % name))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        sys.exit("%d check(s) failed" % len(failures))
    print("all checks passed")


if __name__ == "__main__":
    main()
