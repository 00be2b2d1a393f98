#!/usr/bin/env python3
"""Checks the stream receiver's ELF (make firmware-stream) against its bake and its board.

Promise: prints one line per check, "ok - fw: ..." or "not ok - fw: ...: why", and exits 1 if any
failed. The checks:
  1. no heap symbol (check_elf.py's list), as for every firmware;
  2. no model: no symbol of the bake (mc_model_NAME, mc_octree_NAME, mc_NAME_*, mc_app_model), so
     the model can only come over the wire;
  3. the receive buffer is budget.json's stream buffer (MC_NAME_STREAM_BYTES), the frame buffers its
     ram.color_buffer and ram.depth_buffer; with a mesh part, the level-of-detail memory its
     ram.pmesh_lod, pmesh_facing (each rounded up to whole words), pmesh_cache and pmesh_sdepth;
  4. fits the board: flash and static RAM plus the stack reservation within the .ld's sizes;
  5. the static stack bound (stack_bound.py, the renderer at the bake's depth) fits the reservation
     and the RAM above the static data.
Then one line "firmware NAME: flash F B, static RAM R B, ..." with the figures.
Usage: check_stream_elf.py --elf ELF --budget budget.json --ld BOARD.ld --obj OBJDIR
"""
import argparse
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_elf  # noqa: E402
import stack_bound  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--elf", required=True)
    ap.add_argument("--budget", required=True)
    ap.add_argument("--ld", required=True)
    ap.add_argument("--obj", required=True)
    a = ap.parse_args()
    check = check_elf.Checks()

    budget = json.load(open(a.budget))
    board = check_elf.ld_symbols(a.ld)
    elfname = os.path.basename(a.elf)
    model = budget.get("model", "")
    syms = check_elf.nm_symbols(a.elf)

    heap = sorted(s for s in syms if check_elf.HEAP.match(s))
    check(f"{elfname}: no heap symbols in arm-none-eabi-nm", "found " + " ".join(heap) if heap else "")
    baked = re.compile(rf"^(mc_model_{model}|mc_octree_{model}|mc_{model}_\w+|mc_app_model)$")
    found = sorted(s for s in syms if baked.match(s))
    check(f"{elfname}: links no model (no mc_model_{model}, mc_{model}_*, mc_app_model symbol)",
          "found " + " ".join(found[:5]) if found else "")

    ram = budget.get("ram", {})
    want = {"stream_buf": budget.get("stream", {}).get("buffer"), "color_buf": ram.get("color_buffer"),
            "depth_buf": ram.get("depth_buffer")}
    bad = [f"{k}: ELF {syms.get(k)} vs budget {v}" for k, v in want.items() if v is None or syms.get(k) != v]
    check(f"{elfname}: receive buffer of budget.json's stream buffer ({want['stream_buf']}) and frame buffers "
          f"of its sizes ({want['color_buf']} + {want['depth_buf']})", "; ".join(bad))
    if "pmesh_lod" in ram:
        words = lambda n: (n + 3) // 4 * 4
        mesh = {"pmesh_anc": words(ram["pmesh_lod"]), "pmesh_facing": words(ram["pmesh_facing"]),
                "pmesh_cache": ram.get("pmesh_cache"), "pmesh_sdepth": ram.get("pmesh_sdepth")}
        bad = [f"{k}: ELF {syms.get(k)} vs budget {v}" for k, v in mesh.items() if v is None or syms.get(k) != v]
        check(f"{elfname}: mesh memory of budget.json's sizes ({', '.join(f'{k} {v}' for k, v in mesh.items())})",
              "; ".join(bad))

    ram0, rs, fs = board.get("__ram", 0x20000000), board.get("__ram_size"), board.get("__flash_size")
    flash, ram_static, stack_reserved = check_elf.section_totals(a.elf, ram0)
    check(f"{elfname}: fits the board: flash {flash} of {fs}, RAM {ram_static} + stack {stack_reserved} of {rs}",
          "" if fs and rs and flash <= fs and ram_static + stack_reserved <= rs else "does not fit")

    total, path, _ = stack_bound.bound(a.elf, a.obj, int(budget["depth"]))
    room = rs - ram_static if rs else 0
    print(f"# {elfname}: stack bound {total} bytes: " + " > ".join(n.split(":")[-1] for _, n in path))
    check(f"{elfname}: stack bound {total} fits the reservation __stack_size {stack_reserved} and the "
          f"{room} bytes of RAM above the static data",
          "" if total <= stack_reserved and total <= room else f"bound {total} > reservation or room")
    print(f"firmware {elfname}: flash {flash} B (runtime and receiver), static RAM {ram_static} B "
          f"(stream {want['stream_buf']}, frames {(want['color_buf'] or 0) + (want['depth_buf'] or 0)}), "
          f"stack bound {total} B, RAM with stack {ram_static + total} B of {rs}")
    return 1 if check.fails else 0


if __name__ == "__main__":
    sys.exit(main())
