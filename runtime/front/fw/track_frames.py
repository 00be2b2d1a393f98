#!/usr/bin/env python3
"""The firmware tracker's stored data (make firmware-track): frames of a real sequence shrunk on the
host to the bake's screen, the camera and the start pose, as C for runtime/front/fw/track_main.c,
and the same frames as PGM files with the host tracker's arguments, so that both track the same pixels
with the same settings.

Promise: reads frames FIRST .. FIRST + COUNT - 1 of PATTERN (binary PGM, maxval 255, all one size),
shrinks each K times, K the least whole number that fits the screen (as NAME-track chooses it) or
--scale, by the tracker's box average (runtime/front/common/track_frame.c: each output pixel the
rounded mean of its K x K block, (sum + K^2 / 2) / K^2 in integers, the last w mod K columns and h mod
K rows dropped), and writes
  --c FILE      `static const uint8_t` arrays of the shrunk frames and the constants track_main.c
                declares: size, first frame number, K, particles, the camera's px, py, u0, v0 (the
                first <camera> element's first of each, as NAME-track reads ViSP's XML) and the start
                pose (the six numbers of the .pos file), both as C99 hexadecimal floating constants:
                the exact doubles of the decimal text, so that the firmware starts from the same
                numbers the host's readers give;
  --pgm DIR     DIR/image%04d.pgm (the frame numbers kept) and DIR/host-args: the host tracker's
                arguments for the same run (--frames DIR/image%04d.pgm --shrunk K --first --count
                --camera --init --particles), one a line;
  --budget IN --budget-out OUT   (optional) the bake's budget.json with the frames added to
                flash.arrays and to flash.image, for check_elf.py.
Exits 1 with one line "track_frames.py: ..." on any fault (a missing or odd file, a frame too small).
"""
import argparse
import json
import os
import re
import sys


def die(msg):
    print(f"track_frames.py: {msg}", file=sys.stderr)
    sys.exit(1)


def read_pgm(path):
    try:
        data = open(path, "rb").read()
    except OSError as e:
        die(f"{path}: cannot open: {e.strerror}")
    # header: P5, width, height, maxval, '#' comments between them, then one whitespace byte
    fields, i = [], 2
    if data[:2] != b"P5":
        die(f"{path}: not a binary PGM (P5)")
    while len(fields) < 3:
        while i < len(data) and data[i:i + 1].isspace():
            i += 1
        if data[i:i + 1] == b"#":
            while i < len(data) and data[i:i + 1] != b"\n":
                i += 1
            continue
        j = i
        while j < len(data) and data[j:j + 1].isdigit():
            j += 1
        if j == i:
            die(f"{path}: byte {i}: expected a number in the header")
        fields.append(int(data[i:j]))
        i = j
    w, h, maxval = fields
    if maxval != 255:
        die(f"{path}: maxval {maxval}: only 8-bit frames (255) are stored")
    i += 1
    if len(data) < i + w * h:
        die(f"{path}: byte {len(data)}: {w}x{h} raster cut short")
    return w, h, data[i:i + w * h]


def shrink(px, w, k, dw, dh):
    n = k * k
    out = bytearray(dw * dh)
    for y in range(dh):
        rows = [px[(y * k + j) * w:(y * k + j) * w + dw * k] for j in range(k)]
        for x in range(dw):
            s = sum(sum(r[x * k:x * k + k]) for r in rows)
            out[y * dw + x] = (s + n // 2) // n
    return bytes(out)


def read_camera(path):
    try:
        text = open(path, encoding="utf-8", errors="replace").read()
    except OSError as e:
        die(f"{path}: cannot open: {e.strerror}")
    text = re.sub(r"<!--.*?-->", "", text, flags=re.S)
    m = re.search(r"<camera\b[^>]*>(.*?)</camera>", text, re.S)
    if not m:
        die(f"{path}: no <camera> element")
    cam = {}
    for k in ("px", "py", "u0", "v0"):
        v = re.search(rf"<{k}>\s*([^<]*?)\s*</{k}>", m.group(1))
        if not v:
            die(f"{path}: <camera> has no <{k}>")
        cam[k] = (v.group(1), float(v.group(1)))
    return [cam[k] for k in ("px", "py", "u0", "v0")]


def read_pose(path):
    try:
        lines = open(path, encoding="utf-8", errors="replace").read().splitlines()
    except OSError as e:
        die(f"{path}: cannot open: {e.strerror}")
    words = [w for line in lines for w in line.split("#", 1)[0].split()]
    if len(words) != 6:
        die(f"{path}: {len(words)} numbers, expected 6")
    return [(w, float(w)) for w in words]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--frames", required=True, help="printf pattern of the frames, e.g. DIR/image%%04d.pgm")
    ap.add_argument("--camera", required=True, help="ViSP tracker settings XML")
    ap.add_argument("--init", required=True, help="ViSP .pos file of the first frame's pose")
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--count", type=int, default=8)
    ap.add_argument("--screen", required=True, help="the bake's --screen, WxH")
    ap.add_argument("--scale", type=int, default=0, help="shrink K times (default: the least that fits)")
    ap.add_argument("--particles", type=int, required=True)
    ap.add_argument("--c", required=True, dest="c_out")
    ap.add_argument("--pgm", required=True)
    ap.add_argument("--budget")
    ap.add_argument("--budget-out")
    a = ap.parse_args()
    m = re.fullmatch(r"(\d+)x(\d+)", a.screen)
    if not m:
        die(f"--screen {a.screen}: expected WxH")
    sw, sh = int(m.group(1)), int(m.group(2))
    if a.count < 1:
        die("--count must be at least 1")

    frames, size = [], None
    for i in range(a.first, a.first + a.count):
        path = a.frames % i
        w, h, px = read_pgm(path)
        if size and (w, h) != size:
            die(f"{path}: {w}x{h}, not the size of the first frame {size[0]}x{size[1]}")
        size = (w, h)
        frames.append(px)
    fw, fh = size
    k = a.scale
    if not k:
        k = 1
        while fw // k > sw or fh // k > sh:
            k += 1
    w, h = fw // k, fh // k
    if w > sw or h > sh or w < 3 or h < 3:
        die(f"{fw}x{fh} shrunk {k} times is {w}x{h}; the bake holds {sw}x{sh}")
    small = [shrink(px, fw, k, w, h) for px in frames]
    cam = read_camera(a.camera)
    pose = read_pose(a.init)

    os.makedirs(a.pgm, exist_ok=True)
    for i, px in enumerate(small):
        with open(os.path.join(a.pgm, "image%04d.pgm" % (a.first + i)), "wb") as f:
            f.write(b"P5\n%d %d\n255\n" % (w, h) + px)
    host_args = ["--frames", os.path.join(a.pgm, "image%04d.pgm"), "--shrunk", str(k), "--first", str(a.first),
                 "--count", str(a.count), "--camera", a.camera, "--init", a.init, "--particles", str(a.particles)]
    with open(os.path.join(a.pgm, "host-args"), "w") as f:
        f.write("\n".join(host_args) + "\n")

    names = [f"mc_fw_track_frame_{i}" for i in range(a.count)]
    L = [f"/* Generated by runtime/front/fw/track_frames.py: frames {a.first}..{a.first + a.count - 1} of",
         f" * {a.frames} ({fw}x{fh}) shrunk {k} times to {w}x{h}, the camera of {a.camera} and the",
         f" * start pose of {a.init}, for runtime/front/fw/track_main.c. Not to be edited or committed. */",
         "#include <stdint.h>", "",
         f"const uint16_t mc_fw_track_width = {w}, mc_fw_track_height = {h};",
         f"const uint32_t mc_fw_track_count = {a.count}, mc_fw_track_first = {a.first}, mc_fw_track_scale = {k};",
         f"const uint32_t mc_fw_track_particles = {a.particles};",
         "/* px, py, u0, v0 in pixels of the camera's own frames: " + ", ".join(t for t, _ in cam) + " */",
         "const double mc_fw_track_camera[4] = {" + ", ".join(v.hex() for _, v in cam) + "};",
         "/* tx, ty, tz (m), tux, tuy, tuz (rad): " + ", ".join(t for t, _ in pose) + " */",
         "const double mc_fw_track_init[6] = {" + ", ".join(v.hex() for _, v in pose) + "};", ""]
    for name, px in zip(names, small):
        L.append(f"static const uint8_t {name}[{w * h}] = {{")
        for r in range(0, len(px), 24):
            L.append("    " + ",".join(str(b) for b in px[r:r + 24]) + ",")
        L.append("};")
    L.append(f"const uint8_t *const mc_fw_track_frames[{a.count}] = {{" + ", ".join(names) + "};")
    tmp = a.c_out + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(L) + "\n")
    os.replace(tmp, a.c_out)

    if a.budget and a.budget_out:
        b = json.load(open(a.budget))
        for name in names:
            b["flash"]["arrays"][name] = w * h
        b["flash"]["arrays"]["mc_fw_track_frames"] = 4 * a.count   # the pointer table (32-bit)
        added = a.count * (w * h + 4)
        for key in ("total", "image"):
            if key in b["flash"]:
                b["flash"][key] += added
        b["flash"]["note_frames"] = (f"flash.arrays, total and image include the {a.count} stored frames of "
                                     f"{w}x{h} and their pointer table ({added} bytes), added by track_frames.py")
        json.dump(b, open(a.budget_out, "w"), indent=2, sort_keys=True)
    print(f"track_frames.py: {a.count} frames {fw}x{fh} shrunk {k} times to {w}x{h} into {a.c_out} and {a.pgm}/")


if __name__ == "__main__":
    main()
