"""The report tests' models and a reader for the data a report carries.

    report_models.py blocks FILE.obj   writes the four-block assembly

The assembly: a and b touch on x = 1; b and c stand 0.3 apart (x = 2 .. 2.3); c and d clash over a
0.5 x 10 x 10 slab (x = 2.8 .. 3.3). a, b and c are 1 thick along x (thin below 1.2).
"""
import json
import re
import sys

BLOCKS = [("a", (0, 0, 0), (1, 1, 1)), ("b", (1, 0, 0), (2, 1, 1)), ("c", (2.3, -1, -1), (3.3, 11, 11)),
          ("d", (2.8, 0, 0), (12.8, 10, 10))]


def write_blocks(path):
    """The assembly as OBJ, one object per block, closed and wound outward (as tests/cli/lib.sh box_obj)."""
    faces = [(0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5), (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3), (0, 2, 3),
             (0, 3, 1), (4, 5, 7), (4, 7, 6)]
    with open(path, "w") as f:
        for k, (name, lo, hi) in enumerate(BLOCKS):
            f.write("o %s\n" % name)
            for i in range(8):
                f.write("v %r %r %r\n" % tuple(hi[a] if i >> a & 1 else lo[a] for a in range(3)))
            for t in faces:
                f.write("f %d %d %d\n" % tuple(8 * k + v + 1 for v in t))


def report_data(html):
    """The JSON a report page carries in <script id="pierce-data">."""
    m = re.search(r'<script type="application/json" id="pierce-data">(.*?)</script>', html, re.S)
    if not m:
        raise ValueError("no pierce-data element")
    return json.loads(m.group(1))


# What makes a browser load something: an attribute naming a resource (src, href, srcset,
# poster; in markup, not a script's property as `img.src=`) unless it is an anchor in the page
# (#...) or inline (data:, blob:); a CSS url(...) that is not data:; an @import. (URLs in the
# scripts' comments and XML namespace names, such as http://www.w3.org/2000/svg, load nothing.)
RESOURCE_ATTRIBUTE = re.compile(r"""(?<![.\w$-])(src|href|srcset|poster)\s*=\s*(["']?)([^"'\s>]*)""", re.I)
CSS_LOAD = re.compile(r"""(?<![\w.$])url\(\s*["']?(?!data:)[^)]|@import\b""")


def network_references(html):
    """Every place in `html` that would load something from outside the file."""
    refs = []
    for m in RESOURCE_ATTRIBUTE.finditer(html):
        if not re.match(r"(#|data:|blob:)", m.group(3), re.I):
            refs.append(html[m.start():m.end()])
    refs += [html[m.start():m.start() + 60] for m in CSS_LOAD.finditer(html)]
    return refs


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] != "blocks":
        sys.exit(__doc__)
    write_blocks(sys.argv[2])
