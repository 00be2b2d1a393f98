#!/usr/bin/env python3
"""Compares the frames tests/web/mesh.js read back from a mesh bake's page with the native viewer's.

Usage: mesh_check.py RESULT.json VIEW OUTDIR   (canvas_ppm: for the other mesh pages' checks too)
For each frame: its canvas as OUTDIR/canvasK.ppm, the native viewer's --mode M --lod L at the same
view and size as OUTDIR/nativeK.ppm, then one line "frame K MODE LEVEL FACES YAW same|differs".
First a line "help True|False": whether the page's help line names the mesh keys. A page that gave
no result prints "error ..." only.
"""
import base64
import json
import subprocess
import sys


def canvas_ppm(r, rgba_b64, path):
    """The canvas of a page's result r (width, height) from its base64 RGBA, written to path as a
    binary PPM; returns the PPM's bytes."""
    rgba = base64.b64decode(rgba_b64)
    ppm = b"P6\n%d %d\n255\n" % (r["width"], r["height"]) + bytes(b for i, b in enumerate(rgba) if i % 4 != 3)
    open(path, "wb").write(ppm)
    return ppm


def main():
    result, view, out = sys.argv[1:4]
    try:
        r = json.load(open(result))
    except ValueError:
        print("error no result from the page")
        return 0
    w, h = r["width"], r["height"]
    print("help", "m: points / shaded / lines / shaded+lines" in r["help"])
    for k, f in enumerate(r["frames"]):
        canvas = canvas_ppm(r, f["rgba"], f"{out}/canvas{k}.ppm")
        v = f["rest"]
        n = subprocess.run([view, "--size", f"{w}x{h}", "--mode", v["mode"], "--lod", str(v["level"]),
                            "--yaw", str(v["yaw"] * 360 / 4096), "--pitch", str(v["pitch"] * 360 / 4096),
                            "--zoom", str(v["zoom"] / 65536), "--ppm", f"{out}/native{k}.ppm"],
                           capture_output=True, text=True)
        same = n.returncode == 0 and open(f"{out}/native{k}.ppm", "rb").read() == canvas
        print("frame", k, v["mode"], v["level"], v["faces"], v["yaw"], "same" if same else "differs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
