#!/usr/bin/env python3
"""Compares the stream receiver firmware's output under QEMU with the host viewer's; run by make
firmware-stream-run.

Promise: exits 0 and prints one "firmware-stream-run: ..." line when all of these hold, else prints
what differs on stderr and exits 1:
  - the run is whole: the banner, then for each level D = 1, 2, ... in turn "level D drawable after
    N bytes" and the checksum lines of frames 0..F-1 at depth D, then the final line, the stack line
    and "done"; QEMU's exit status 0 for a complete stream with every render MC_OK, 1 for a stream
    error (a timeout, a fault or a missing line is a failure);
  - each level's lines equal the host viewer's --stream on the first N bytes of the stream (the
    bytes the firmware had when it drew them: the host draws the same level) and, when the stream
    has the bake's header, its --checksums --depth D (the baked arrays, not the reader), and N is
    budget.json's stream.drawable_at for that level;
  - the final state is the host's --stream on the whole file: complete at the same depth and bytes
    (or, for bytes after the end record, which the firmware never reads, the host's "trailing" error
    there), or the same error name, byte offset and depth kept (the last level the firmware drew);
    a mesh larger than the firmware's mesh memory ("mesh-size") is one the host refuses too;
  - a receiver built with a mesh (make firmware-stream FW_MESH=1) prints, each time more of the mesh
    has come, "mesh level L of V drawable after N bytes" (then "mesh complete after N bytes" for the
    adjacency) and the mesh frames, the levels L rising; each block equals the host's --stream
    --checksums on the first N bytes, the last one its --stream --checksums on the whole file (so a
    run draws a mesh exactly when the host does), and a complete mesh's, for the bake's own stream,
    its --checksums (the baked arrays).
Usage: stream_check.py --run RUN.txt --status QEMU_STATUS --view NAME-view --stream FILE --work DIR
"""
import argparse
import json
import os
import re
import subprocess
import sys

BANNER = re.compile(r"^modelc stream firmware: buffer (\d+) bytes .* frames (\d+) a level")
LEVEL = re.compile(r"^level (\d+) drawable after (\d+) bytes$")
FRAME = re.compile(r"^frame (\d+) .* depth (\d+) level ")
COMPLETE = re.compile(r"^stream complete: depth (\d+), (\d+) bytes$")
MESH = re.compile(r"^mesh (?:complete|level (\d+) of \d+ drawable) after (\d+) bytes$")
MESH_FRAME = re.compile(r"^mesh frame (\d+) ")
ERROR = re.compile(r"^stream error ([\w-]+) at byte (\d+) after (\d+) bytes(?: \([^)]*\))?; keeping depth (\d+)")
HOST_COMPLETE = re.compile(r"^stream: complete, depth (\d+), (\d+) bytes$")
HOST_ERROR = re.compile(r"stream: (\w+) at byte (\d+); (?:drawing depth (\d+)|nothing was drawable)")


def host(view, args, data=None):
    r = subprocess.run([view] + args, input=data, capture_output=True)
    return r.returncode, r.stdout.decode(errors="replace").splitlines(), r.stderr.decode(errors="replace")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--run", required=True)
    ap.add_argument("--status", type=int, required=True)
    ap.add_argument("--view", required=True)
    ap.add_argument("--stream", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    why = []
    lines = [l.rstrip("\r\n") for l in open(a.run, errors="replace")]
    data = open(a.stream, "rb").read()
    bake = os.path.dirname(os.path.abspath(a.view))
    name = os.path.basename(a.view)[:-len("-view")]
    baked = open(os.path.join(bake, name + ".mcs"), "rb").read()
    own = data[:20] == baked[:20]   # the bake's own header: its levels are the bake's
    drawable_at = json.load(open(os.path.join(bake, "budget.json")))["stream"]["drawable_at"]

    # ---- the firmware's run, in order --------------------------------------------------------------
    banner = [m for m in map(BANNER.match, lines) if m]
    frames = int(banner[0].group(2)) if banner else 0
    levels = []   # (depth, bytes, [frame lines])
    meshes = []   # (level or None for complete, bytes, [mesh frame lines])
    final = None
    i = 0
    while i < len(lines):
        m = MESH.match(lines[i])
        if m:
            block = []
            while i + 1 < len(lines) and MESH_FRAME.match(lines[i + 1]):
                block.append(lines[i + 1])
                i += 1
            if [int(MESH_FRAME.match(l).group(1)) for l in block] != list(range(len(block))) or not block:
                why.append(f"{lines[i - len(block)]}: not a run of mesh frames numbered 0, 1, ... after it")
            meshes.append((int(m.group(1)) if m.group(1) else None, int(m.group(2)), block))
            i += 1
            continue
        m = LEVEL.match(lines[i])
        if m:
            d, n = int(m.group(1)), int(m.group(2))
            block = lines[i + 1:i + 1 + frames]
            ok = len(block) == frames and all(
                (f := FRAME.match(l)) and int(f.group(1)) == k and int(f.group(2)) == d for k, l in enumerate(block))
            if not ok:
                why.append(f"level {d}: not {frames} frame lines at depth {d} after it")
            levels.append((d, n, block))
            i += 1 + frames
            continue
        if COMPLETE.match(lines[i]) or ERROR.match(lines[i]):
            final = lines[i]
        i += 1
    if not banner:
        why.append("no banner line")
    if [d for d, _, _ in levels] != list(range(1, len(levels) + 1)):
        why.append(f"levels drawn {[d for d, _, _ in levels]}, not 1, 2, ... in turn")
    if final is None or "done" not in lines or lines.index("done") < lines.index(final):
        why.append(f"no final line and \"done\" (QEMU status {a.status}): {' | '.join(lines[-3:])}")
        final = ""
    fc, fe = COMPLETE.match(final), ERROR.match(final)
    rc_bad = any(" rc 0 " not in l for _, _, b in levels + meshes for l in b)
    want_status = 0 if fc and not rc_bad else 1
    if a.status != want_status:
        why.append(f"QEMU exit status {a.status}, expected {want_status} (124: the timeout)")
    kept = levels[-1][0] if levels else 0
    if (fc and int(fc.group(1)) != kept) or (fe and int(fe.group(4)) != kept):
        why.append(f"final line says depth {(fc or fe).groups()}, the last level drawn is {kept}")

    # ---- each level against the host -----------------------------------------------------------------
    compared = 0
    for d, n, block in levels:
        st, out, err = host(a.view, ["--stream", "-", "--checksums"], data[:n])
        hf = [l for l in out if l.startswith("frame ")][:frames]
        if hf != block:
            why.append(f"level {d}: the firmware's frames differ from --stream on the first {n} bytes "
                       f"(exit {st}, {len(hf)} lines: {err.strip()[:200]})")
        if own:
            if d <= len(drawable_at) and drawable_at[d - 1] != n:
                why.append(f"level {d} drawn after {n} bytes, budget.json's drawable_at says {drawable_at[d - 1]}")
            st, out, err = host(a.view, ["--checksums", "--depth", str(d)])
            if out[:frames] != block:
                diff = [f"fw: {x} | host: {y}" for x, y in zip(block, out[:frames]) if x != y][:2]
                why.append(f"level {d}: the firmware's frames differ from --checksums --depth {d}: {diff}")
        compared += len(block)
        with open(os.path.join(a.work, f"level{d}.txt"), "w") as f:
            f.write("\n".join(block) + "\n")

    # ---- the final state against the host's --stream on the whole file ----------------------------------
    st, out, err = host(a.view, ["--stream", a.stream, "--checksums"])
    with open(os.path.join(a.work, "host-stream.txt"), "w") as f:
        f.write("\n".join(out) + "\n" + err)
    hc = [m for m in map(HOST_COMPLETE.match, out) if m]
    he = HOST_ERROR.search(err)
    if fe and fe.group(1) == "mesh-size":
        if st == 0 or "larger than this viewer's mesh buffers" not in err:
            why.append(f"firmware: {final}; host --stream: exit {st} {err.strip()[:200]}")
    elif fc and he and he.group(1) == "trailing" and he.group(2) == fc.group(2) and he.group(3) == fc.group(1):
        pass   # bytes after the end record: the firmware stops reading there, the host reads on to the file's end
    elif fc:
        if st != 0 or not hc or hc[-1].groups() != fc.groups():
            why.append(f"firmware: {final}; host --stream: exit {st} {(hc[-1].group(0) if hc else err.strip())}")
    elif fe:
        if st == 0 or not he or (he.group(1), he.group(2), he.group(3) or "0") != (fe.group(1), fe.group(2), fe.group(4)):
            why.append(f"firmware: {final}; host --stream: exit {st} {err.strip()[:200]}")
    if levels and (fc or fe):
        hf = [l for l in out if l.startswith("frame ")][:frames]
        if hf != levels[-1][2]:
            why.append(f"the last level's frames differ from --stream on the whole file's ({len(hf)} lines)")


    # ---- the mesh frames against the host ----------------------------------------------------------------
    host_mesh = [l for l in out if l.startswith("mesh frame ")]
    if (meshes[-1][2] if meshes else []) != host_mesh:
        why.append(f"the last mesh frames drawn ({len(meshes[-1][2]) if meshes else 0} lines) differ from --stream "
                   f"on the whole file's ({len(host_mesh)} lines)")
    drawn = [lv for lv, _, _ in meshes if lv is not None]
    if drawn != sorted(set(drawn)) or any(lv is None for lv, _, _ in meshes[:-1]):
        why.append(f"mesh levels drawn {[lv if lv is not None else 'complete' for lv, _, _ in meshes]}: not rising, "
                   f"complete last")
    for lv, n, block in meshes:
        st, out, err = host(a.view, ["--stream", "-", "--checksums"], data[:n])
        if [l for l in out if l.startswith("mesh frame ")] != block:
            why.append(f"mesh {lv or 'complete'}: the mesh frames differ from --stream on the first {n} bytes "
                       f"(exit {st}: {err.strip()[:200]})")
        if own and lv is None:
            st, out, err = host(a.view, ["--checksums"])
            hm = [l for l in out if l.startswith("mesh frame ")]
            if hm != block:
                diff = [f"fw: {x} | host: {y}" for x, y in zip(block, hm) if x != y][:2]
                why.append(f"the mesh frames differ from --checksums (the baked mesh): {len(hm)} lines, {diff}")
    with open(os.path.join(a.work, "mesh.txt"), "w") as f:
        f.write("".join(f"{lv or 'complete'} {n}\n" + "\n".join(b) + "\n" for lv, n, b in meshes))

    if why:
        for w in why:
            print(f"firmware-stream-run: {w}", file=sys.stderr)
        return 1
    drew = (f"levels 1..{kept}: {compared} frame checksums equal the host viewer's (--stream on each level's "
            f"bytes{', --checksums --depth D' if own else ''})" if levels else "no level drawable, as for the host")
    if meshes:
        whole = [n for lv, n, _ in meshes if lv is None]
        drew += (f"; the mesh at {len([1 for lv, _, _ in meshes if lv is not None])} levels as they came"
                 f"{f', whole after {whole[0]} bytes' if whole else ''}: {sum(len(b) for _, _, b in meshes)} mesh "
                 f"frame checksums equal the host viewer's (--stream on each block's bytes"
                 f"{', --checksums' if own and whole else ''})")
    print(f"firmware-stream-run: {drew}; final state as the host viewer's --stream: {final}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
