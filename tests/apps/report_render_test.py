#!/usr/bin/env python3
"""`delmesh report` drawn by a browser: meshes the torus, writes its page, checks that the page
loads nothing from elsewhere, renders it in headless Chromium and checks that the screenshot's
3-D view shows a coloured mesh (not the blank background, not only text).

Usage: report_render_test.py DELMESH [CHROMIUM].  Exit code 77 (a skip for CTest) when no
Chromium is found (CHROMIUM, $DELMESH_CHROMIUM, or chromium / chromium-browser / google-chrome on
PATH); 0 when the check passes, 1 otherwise.  Python's standard library only (its own PNG reader).
"""

import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

SKIP = 77
# The window, and the region of the 3-D view inside it (apps/report_html.cpp lays the view out
# at the left, 28 px from the edge, below a header of about 56 px, beside a 300 px panel).
WIDTH, HEIGHT = 1200, 900
VIEW = (60, 90, 800, 680)  # x0, y0, x1, y1


def read_png(path):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit, non-interlaced RGB or RGBA PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG file")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"unsupported PNG (depth {depth}, colour type {colour}, interlace {interlace})")
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous, at = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[at], bytearray(raw[at + 1:at + 1 + stride])
        at += 1 + stride
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            up_left = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else up_left)) & 255
        rows.append([tuple(line[j:j + 3]) for j in range(0, stride, channels)])
        previous = line
    return width, height, rows


def find_chromium(argv):
    for candidate in ([argv[2]] if len(argv) > 2 and argv[2] else []) + [os.environ.get("DELMESH_CHROMIUM", "")]:
        if candidate and shutil.which(candidate):
            return shutil.which(candidate)
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    return None


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main(argv):
    delmesh = os.path.abspath(argv[1])
    chromium = find_chromium(argv)
    if not chromium:
        print("SKIP: no Chromium (chromium, chromium-browser or google-chrome) found")
        return SKIP
    with tempfile.TemporaryDirectory(prefix="delmesh_report_") as work:
        def run(*args):
            r = subprocess.run([delmesh, *args], cwd=work, capture_output=True, text=True, timeout=300)
            if r.returncode != 0:
                fail(f"delmesh {' '.join(args)} exited with {r.returncode}: {r.stderr}")
        run("mesh", "--surface", "torus", "--out", "torus.off", "--stats", "torus.json", "--quiet")
        run("report", "torus.off", "--stats", "torus.json", "--out", "report.html")
        page = os.path.join(work, "report.html")
        with open(page, encoding="utf-8") as f:
            html = f.read()
        # Self-contained: no element loads anything by address, no stylesheet imports.
        remote = re.findall(r"<(?:script|link|img|iframe|source|embed|object)\b[^>]*\b(?:src|href|data)\s*=[^>]*>",
                            html, re.IGNORECASE)
        if remote:
            fail(f"the page loads other files: {remote[:3]}")
        if re.search(r"@import|url\(\s*['\"]?(?:https?:)?//", html, re.IGNORECASE):
            fail("the page's style loads other files")

        shot = os.path.join(work, "shot.png")
        profile = os.path.join(work, "profile")
        command = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
                   "--use-angle=swiftshader", "--disable-quic", "--no-first-run", "--disable-background-networking",
                   "--disable-component-update", "--disable-sync", "--user-data-dir=" + profile,
                   f"--window-size={WIDTH},{HEIGHT}", "--virtual-time-budget=5000", "--screenshot=" + shot,
                   "file://" + page]
        r = subprocess.run(command, capture_output=True, text=True, timeout=120)
        if r.returncode != 0 or not os.path.exists(shot):
            fail(f"chromium exited with {r.returncode} and no screenshot: {r.stderr[-2000:]}")
        keep = os.environ.get("DELMESH_REPORT_SCREENSHOT")
        if keep:
            shutil.copy(shot, keep)
        width, height, rows = read_png(shot)
        if (width, height) != (WIDTH, HEIGHT):
            fail(f"the screenshot is {width}x{height}, expected {WIDTH}x{HEIGHT}")

        # The view's background is white; the torus covers about a third of the view, in the colours
        # of the colour map (saturated), shaded (many distinct colours).
        x0, y0, x1, y1 = VIEW
        pixels = [p for row in rows[y0:y1] for p in row[x0:x1]]
        drawn = [p for p in pixels if sum(255 - c for c in p) > 30]
        coloured = [p for p in drawn if max(p) - min(p) > 60]
        distinct = {(p[0] >> 3, p[1] >> 3, p[2] >> 3) for p in drawn}
        share, coloured_share = len(drawn) / len(pixels), len(coloured) / max(1, len(drawn))
        print(f"3-D view: {100 * share:.1f} % of the pixels drawn, {100 * coloured_share:.1f} % of those coloured, "
              f"{len(distinct)} distinct colours")
        if share < 0.05:
            fail("the 3-D view is blank")
        if coloured_share < 0.3:
            fail("the 3-D view has no coloured mesh (grey or text only)")
        if len(distinct) < 50:
            fail("the 3-D view has too few colours for a shaded, coloured mesh")
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
