"""A registration report as a reader sees it: opened from its folder in
headless Chromium, offline.

Checks that the page loads with the verdict banner first (its class and its
words), that the interactive 3-D view drew (the viewer reports the pixels
it drew in its canvas's data-status), that the page asks for nothing from
the network, and that the screenshot shows the banner in its colour. The
screenshot is kept for a person to look at. Only the standard library: the
screenshot's PNG is decoded here. Exits non-zero on any failure.

Usage: python3 CheckReportInBrowser.py <report folder> registered|flagged <screenshot.png>
"""

import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def chromium():
    for name in (os.environ.get("VIMLOP_CHROMIUM", ""), "chromium", "chromium-browser"):
        if name and shutil.which(name):
            return shutil.which(name)
    sys.exit("no chromium: install it with CMake/install-dependencies.sh (Debian package chromium)")


def run_browser(page, *arguments):
    # Offline: every host name fails to resolve, so a page that needs the
    # network shows it. A profile of its own, removed after.
    with tempfile.TemporaryDirectory(prefix="vimlop-chromium-") as profile:
        command = [chromium(), "--headless", "--no-sandbox", "--no-first-run",
                   "--user-data-dir=" + profile, "--host-resolver-rules=MAP * ~NOTFOUND",
                   "--virtual-time-budget=10000", "--window-size=1000,1400", *arguments,
                   "file://" + os.path.abspath(page)]
        done = subprocess.run(command, capture_output=True, text=True, timeout=240)
    if done.returncode != 0:
        sys.exit("chromium failed (%d): %s" % (done.returncode, done.stderr[-2000:]))
    return done.stdout


def png_pixels(path):
    """(width, height, rows of (r, g, b)) of an 8-bit RGB or RGBA PNG without interlacing."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(path + ": not a PNG")
    at, idat = 8, b""
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace:
                sys.exit(path + ": not an 8-bit RGB(A) PNG without interlacing")
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = line[x - channels] if x >= channels else 0
            up = previous[x]
            corner = previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + left) & 255
            elif kind == 2:
                line[x] = (line[x] + up) & 255
            elif kind == 3:
                line[x] = (line[x] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[x] = (line[x] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append([tuple(line[i:i + 3]) for i in range(0, stride, channels)])
        previous = line
    return width, height, rows


def main():
    if len(sys.argv) != 4 or sys.argv[2] not in ("registered", "flagged"):
        sys.exit(__doc__)
    folder, status, screenshot = sys.argv[1:]
    page = os.path.join(folder, "index.html")
    if not os.path.isfile(page):
        sys.exit(page + ": no report there")

    # Nothing from the network: every file the page names is in its folder.
    for name in ("index.html", "view3d.js"):
        text = open(os.path.join(folder, name), encoding="utf-8").read()
        check(not re.search(r"(src|href)\s*=\s*\"(https?:)?//", text) and "http://" not in text
              and "https://" not in text, name + " refers to nothing on the network")
    for source in re.findall(r"src=\"([^\"]+)\"", open(page, encoding="utf-8").read()):
        check(os.path.isfile(os.path.join(folder, source)), "the page's '%s' is in the folder" % source)

    dom = run_browser(page, "--dump-dom")
    banner = re.search(r"<div id=\"verdict\" class=\"verdict (\w+)\">([^<]*)</div>", dom)
    check(banner is not None, "the page has a verdict banner")
    words = {"registered": "REGISTERED: contour error", "flagged": "FLAGGED AS A FAILURE, do not navigate"}
    if banner:
        check(banner.group(1) == status, "the banner says %s (it says %s)" % (status, banner.group(1)))
        check(banner.group(2).startswith(words[status]), "the banner reads '%s'" % banner.group(2))
        check(dom.find(banner.group(0)) < dom.find("<h2>"), "the banner comes before every section")
    drawn = re.search(r"data-status=\"drawn: (\d+) triangles, (\d+) points, (\d+) cameras; "
                      r"(\d+) pixels drawn, (\d+) of them points\"", dom)
    check(drawn is not None, "the interactive view drew (data-status: %s)"
          % (re.search(r"data-status=\"([^\"]*)\"", dom) or [None, "none"])[1])
    if drawn:
        triangles, points, cameras, pixels, red = (int(g) for g in drawn.groups())
        print("interactive view: %d triangles, %d points, %d cameras; %d of 480000 pixels drawn, %d red"
              % (triangles, points, cameras, pixels, red))
        check(triangles > 1000 and cameras > 0, "the view holds the airway and the cameras")
        check(pixels > 0.05 * 800 * 600, "the airway covers more than 5 % of the canvas")
        check(points == 0 or red > 0, "registered points are seen")

    run_browser(page, "--screenshot=" + os.path.abspath(screenshot), "--hide-scrollbars")
    width, height, rows = png_pixels(screenshot)
    colour = {"registered": (27, 122, 46), "flagged": (179, 22, 27)}[status]
    banner_pixels = sum(1 for row in rows[:300] for pixel in row
                        if sum(abs(a - b) for a, b in zip(pixel, colour)) < 30)
    print("screenshot %s: %d x %d, %d banner-coloured pixels in the top 300 rows"
          % (screenshot, width, height, banner_pixels))
    check(banner_pixels > 20000, "the screenshot shows the %s banner in its colour" % status)

    if failures:
        sys.exit("%d check(s) failed" % len(failures))
    print("report in the browser: all checks passed")


main()
