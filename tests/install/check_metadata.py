"""Checks that LICENSE, freecad_addon/package.xml and the ParaView plugin's CMake agree with the
project's metadata (CMake: PROJECT_VERSION, PIERCE_LICENSE, PIERCE_MAINTAINER_*). Prints
"metadata ok" and exits 0, or lists every mismatch and exits 1."""
import argparse
import os
import re
import sys
import xml.etree.ElementTree as ET

NS = {"p": "https://wiki.freecad.org/Package_Metadata"}
# First line of LICENSE for each SPDX identifier the project might use.
LICENSE_TITLES = {"BSD-3-Clause": "BSD 3-Clause License", "MIT": "MIT License",
                  "LGPL-2.1-or-later": "GNU LESSER GENERAL PUBLIC LICENSE"}


def main():
    ap = argparse.ArgumentParser()
    for name in ("source", "version", "license", "maintainer-name", "maintainer-email"):
        ap.add_argument("--" + name, required=True)
    a = ap.parse_args()
    errors = []

    def check(cond, what):
        if not cond:
            errors.append(what)

    lic_path = os.path.join(a.source, "LICENSE")
    check(os.path.isfile(lic_path), "no LICENSE file at the top of the repository")
    if os.path.isfile(lic_path):
        first = open(lic_path, encoding="utf-8").readline().strip()
        check(a.license in LICENSE_TITLES, "unknown licence identifier %r" % a.license)
        check(first == LICENSE_TITLES.get(a.license), "LICENSE starts with %r, not the %s title" % (first, a.license))

    addon = os.path.join(a.source, "freecad_addon")
    root = ET.parse(os.path.join(addon, "package.xml")).getroot()

    def text(tag):
        el = root.find("p:" + tag, NS)
        return None if el is None else (el.text or "").strip()

    check(text("version") == a.version, "package.xml version %r != project version %r" % (text("version"), a.version))
    lic = root.find("p:license", NS)
    check(lic is not None and (lic.text or "").strip() == a.license,
          "package.xml licence %r != %r" % (None if lic is None else lic.text, a.license))
    m = root.find("p:maintainer", NS)
    check(m is not None and (m.text or "").strip() == a.maintainer_name and m.get("email") == a.maintainer_email,
          "package.xml maintainer %r <%r> != %r <%r>" % (None if m is None else m.text, None if m is None else m.get("email"),
                                                        a.maintainer_name, a.maintainer_email))
    for el in root.iter():
        for v in list(el.attrib.values()) + [el.text or ""]:
            check("example.invalid" not in v and "NOASSERTION" not in v, "placeholder left in package.xml: %r" % v)
    icons = [root.find("p:icon", NS)] + root.findall("p:content/p:workbench/p:icon", NS)
    for icon in icons:
        check(icon is not None and os.path.isfile(os.path.join(addon, icon.text.strip())),
              "package.xml icon missing: %r" % (None if icon is None else icon.text))
    deps = {(d.get("type"), (d.text or "").strip()) for d in root.findall("p:depend", NS)}
    for dep in (("python", "numpy"), ("python", "pierce"), ("internal", "Part")):
        check(dep in deps, "package.xml lacks the dependency %s" % (dep,))
    wb = root.find("p:content/p:workbench/p:classname", NS)
    initgui = open(os.path.join(addon, "InitGui.py"), encoding="utf-8").read()
    check(wb is not None and re.search(r"class %s\(" % re.escape(wb.text.strip()), initgui),
          "package.xml workbench class not defined in InitGui.py")

    plugin_cmake = open(os.path.join(a.source, "plugins", "paraview", "PierceParaView", "CMakeLists.txt"),
                        encoding="utf-8").read()
    check(re.search(r"paraview_add_plugin\(PierceParaView\s+VERSION \$\{PROJECT_VERSION\}", plugin_cmake),
          "the ParaView plugin does not report the project version (paraview_add_plugin VERSION)")

    for e in errors:
        print("FAIL:", e)
    if errors:
        return 1
    print("metadata ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
