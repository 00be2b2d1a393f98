#!/usr/bin/env python3
"""Checks a linked firmware ELF against its bake's budget.json and its board; run by `make firmware`.

Promise: prints one line per check, "ok - fw: ..." or "not ok - fw: ...: why", and exits 1 if any
failed. The checks:
  1. no heap: arm-none-eabi-nm lists no allocator (malloc, calloc, realloc, free, their _r variants,
     _sbrk/sbrk) and no __wrap_/__real_ symbol. The link used --wrap=malloc,calloc,realloc,free with
     no wrapper definitions, so a heap call would not even link; this confirms nothing else pulled one.
  2. model data exact: every array budget.json lists under flash.arrays is a symbol of exactly that
     size, and the frame buffers (ram.color_buffer, ram.depth_buffer) and, with a mesh part, its state
     (ram.pmesh_lod, pmesh_facing, pmesh_cache, pmesh_sdepth, pmesh_neighbours: the app binding's
     ancestor map, facing bits, vertex cache, sparse depth buffer bits and neighbour table; no symbol
     for an item of 0 bytes) are symbols of exactly those sizes.
  3. ELF against budget totals: flash used (the sections arm-none-eabi-size -A places in flash) minus
     budget.json's flash.image (its estimate of the image), or flash.total (model data only) for an
     older budget.json, and RAM used (sections in RAM except the stack reservation) minus its
     ram.image (or ram.total), each within a stated margin (MARGINS below: what each covers and why);
     the static stack bound against budget.json's stack.bound, when it has one.
  4. fits the board: flash and RAM used within the board's sizes (from its .ld file); the linker
     already refuses an image that does not fit, so this only restates it with numbers.
  5. stack: the static bound from stack_bound.py (-fstack-usage over the call graph) fits the stack
     reservation in the board's .ld (__stack_size) and the RAM left between .bss and the top of RAM.
Usage: check_elf.py --elf ELF --budget budget.json --ld BOARD.ld --obj OBJDIR --depth D
"""
import argparse
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stack_bound  # noqa: E402

# What the ELF holds besides the model data that budget.json counts (flash.total: masks, colours,
# palette; ram.total: the colour and depth buffers). Margins are absolute bytes, so a bake whose
# budget.json starts counting the runtime's code itself (and so lands closer) still passes.
MARGINS = {
    # when budget.json estimates the whole image (flash.image: model data + descriptors + the runtime's
    # code from gen/runtime_costs.hpp): what the estimate leaves out is the front end and the C library
    # - picolibc's integer printf and snprintf ~3 KB, crt0, the vector table and the semihosting calls
    # ~1 KB, the firmware front end (main, ppm_out, stack, counter, mark) ~1.5 KB - plus code size
    # differences between compiler versions and flags (-mcpu=cortex-m3 vs the estimate's cortex-m4).
    # Measured: +5.7 KB on lm3s6965evb (Cortex-M3), +3.1 KB on mps2-an386. 16 KiB catches a runtime
    # that grew past its estimate.
    "flash_image": 16 * 1024,
    # when budget.json gives only the model's data (flash.total): the runtime's code, about 66 KB on Thumb-2: octree_render.c's MC_LEAF_SWITCH=1 leaf switch alone is
    # ~58 KB (one case per mask value, config.h) and the quarter-wave sine table 4 KB; picolibc's
    # integer printf, crt0 and the semihosting calls ~4 KB; libgcc's 64-bit division ~1 KB; the model's
    # descriptors (chunk lists, levels, octree, model: 8-56 bytes each) and the vector table < 1 KB.
    # 96 KiB leaves room for a larger switch from another compiler version, not for a second copy.
    "flash": 96 * 1024,
    # picolibc's static data (stdout FILE, errno, TLS block) and the front end's command-line buffer
    # (160 bytes): under 1 KiB. The stack is checked separately (check 5).
    "ram": 1024,
    # our whole-program bound against budget.json's stack.bound for mc_octree_render alone: crt0 and main
    # (about 60 bytes), two more walk frames (D instead of d-2: about 250 bytes), minus frames the
    # estimate takes from the host compiler where they are larger. 1 KiB.
    "stack": 1024,
}

HEAP = re.compile(r"^(malloc|calloc|realloc|free|reallocarray|aligned_alloc|memalign|posix_memalign|valloc|"
                  r"pvalloc|_sbrk|sbrk|_malloc_r|_calloc_r|_realloc_r|_free_r|__malloc_.*|__wrap_.*|__real_.*)$")


def run(*cmd):
    return subprocess.run(cmd, capture_output=True, text=True, check=True).stdout


def ld_symbols(path):
    vals = {}
    for m in re.finditer(r"^\s*(__\w+)\s*=\s*(0x[0-9a-fA-F]+|\d+)\s*([KM]?)\s*;", open(path).read(), re.M):
        v = int(m.group(2), 0) * {"": 1, "K": 1024, "M": 1024 * 1024}[m.group(3)]
        vals[m.group(1)] = v
    return vals



def nm_symbols(elf):
    """Every symbol of the ELF: its size in bytes (arm-none-eabi-nm -S), or None where nm gives none."""
    syms = {}
    for line in run("arm-none-eabi-nm", "-S", elf).splitlines():
        f = line.split()
        if len(f) == 4:
            syms[f[3]] = int(f[1], 16)
        elif len(f) >= 2:
            syms.setdefault(f[-1], None)
    return syms


class Checks:
    """checks(name, problem): prints "ok - fw: name", or "not ok - fw: name: problem" and counts it."""

    def __init__(self):
        self.fails = 0

    def __call__(self, name, problem):
        print(f"not ok - fw: {name}: {problem}" if problem else f"ok - fw: {name}")
        self.fails += bool(problem)


def section_totals(elf, ram0):
    """(flash, static RAM, stack reservation) from arm-none-eabi-size -A: flash holds every allocated
    section below the RAM's origin plus the initial values of .data; static RAM is every section in
    the RAM region except the stack reservation (.stack)."""
    flash = ram_static = stack_reserved = 0
    for line in run("arm-none-eabi-size", "-A", "-d", elf).splitlines()[2:]:
        f = line.split()
        if len(f) != 3 or not f[1].isdigit() or f[0].startswith((".debug", ".comment", ".ARM.attr")):
            continue
        name, size, addr = f[0], int(f[1]), int(f[2])
        if addr < ram0:
            flash += size
        elif name == ".stack":
            stack_reserved = size
        else:
            ram_static += size
            if name in (".data", ".tdata"):
                flash += size
    return flash, ram_static, stack_reserved

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--elf", required=True)
    ap.add_argument("--budget", required=True)
    ap.add_argument("--ld", required=True)
    ap.add_argument("--obj", required=True)
    ap.add_argument("--depth", type=int, required=True)
    a = ap.parse_args()
    check = Checks()

    budget = json.load(open(a.budget))
    board = ld_symbols(a.ld)
    elfname = os.path.basename(a.elf)

    # 1. no heap
    syms = nm_symbols(a.elf)
    heap = sorted(s for s in syms if HEAP.match(s))
    check(f"{elfname}: no heap symbols in arm-none-eabi-nm (malloc, free, _sbrk, _malloc_r, __wrap_...)",
          "found " + " ".join(heap) if heap else "")

    # 2. model data and buffers exact
    arrays = budget.get("flash", {}).get("arrays", {})
    bad = [f"{k}: ELF {syms.get(k)} vs budget {v}" for k, v in sorted(arrays.items()) if syms.get(k) != v]
    check(f"{elfname}: {len(arrays)} model arrays have exactly budget.json's sizes", "; ".join(bad[:5]))
    model = budget.get("model", "")
    ram = budget.get("ram", {})
    bufs = {"color_buffer": f"mc_{model}_color", "depth_buffer": f"mc_{model}_depth"}
    bad = [f"{sym}: ELF {syms.get(sym)} vs budget {ram.get(k)}" for k, sym in bufs.items()
           if k in ram and syms.get(sym) != ram[k]]
    check(f"{elfname}: frame buffers have exactly budget.json's sizes", "; ".join(bad))
    # the mesh part's state in the app binding (NAME_app.c), with a mesh part (--as both): each its
    # budget's bytes, or those rounded up to whole 32-bit words (an array the binding declares in words
    # for alignment); an item of 0 bytes (a bake without that buffer) must have no symbol
    mesh = {"pmesh_lod": f"mc_{model}_pmesh_anc", "pmesh_facing": f"mc_{model}_pmesh_facing",
            "pmesh_cache": f"mc_{model}_pmesh_cache", "pmesh_sdepth": f"mc_{model}_pmesh_sdepth",
            "pmesh_neighbours": f"mc_{model}_pmesh_nbr"}
    mesh = {k: sym for k, sym in mesh.items() if k in ram}
    if mesh:
        bad = [f"{sym}: ELF {syms.get(sym)} vs budget {ram[k]}" for k, sym in mesh.items()
               if syms.get(sym) not in ({ram[k], (ram[k] + 3) // 4 * 4} if ram[k] else {None})]
        check(f"{elfname}: the mesh part's RAM ({', '.join(mesh)}) has exactly budget.json's sizes",
              "; ".join(bad))

    # 3. totals within the margins (section_totals)
    # section below the RAM's origin plus the initial values of .data; static RAM is every section in
    # the RAM region except the stack reservation (.stack).
    ram0, rs, fs = board.get("__ram", 0x20000000), board.get("__ram_size"), board.get("__flash_size")
    flash_used, ram_static, stack_reserved = section_totals(a.elf, ram0)
    ram_used = ram_static
    fkey, mkey = ("image", "flash_image") if "image" in budget["flash"] else ("total", "flash")
    rkey = "image" if "image" in budget["ram"] else "total"
    bf, br, fm, rm = budget["flash"][fkey], budget["ram"][rkey], MARGINS[mkey], MARGINS["ram"]
    d = flash_used - bf
    print(f"# {elfname}: flash {flash_used} bytes, budget.json flash.{fkey} {bf}: {d:+d} (margin {fm})")
    check(f"{elfname}: flash used within {fm} bytes of budget.json's flash.{fkey}",
          "" if abs(d) <= fm else f"{flash_used} vs {bf}: {d:+d} bytes")
    d = ram_used - br
    print(f"# {elfname}: RAM {ram_used} bytes static (without the stack reservation {stack_reserved}), "
          f"budget.json ram.{rkey} {br}: {d:+d} (margin {rm})")
    check(f"{elfname}: static RAM within {rm} bytes of budget.json's ram.{rkey}",
          "" if abs(d) <= rm else f"{ram_used} vs {br}: {d:+d} bytes")

    # 4. the board
    check(f"{elfname}: fits the board: flash {flash_used} of {fs}, RAM {ram_used} + stack of {rs}",
          "" if fs and rs and flash_used <= fs and ram_used + stack_reserved <= rs else "does not fit")

    # 5. stack
    total, path, indirect = stack_bound.bound(a.elf, a.obj, a.depth)
    room = rs - ram_used if rs else 0
    print(f"# {elfname}: stack bound {total} bytes: " + " > ".join(n.split(":")[-1] for _, n in path))
    sb = budget.get("stack", {}).get("bound") if isinstance(budget.get("stack"), dict) else None
    if sb is not None:
        # budget.json's bound is mc_octree_render's alone (frames the larger of ARM and host, d-2 walk frames);
        # ours adds crt0's and main's frames and counts D walk frames: within a few hundred bytes
        d = total - sb
        print(f"# {elfname}: budget.json stack.bound {sb} (mc_octree_render's): ours {d:+d} (margin {MARGINS['stack']})")
        check(f"{elfname}: stack bound within {MARGINS['stack']} bytes of budget.json's stack.bound",
              "" if abs(d) <= MARGINS["stack"] else f"{total} vs {sb}: {d:+d} bytes")
    check(f"{elfname}: stack bound {total} fits the reservation __stack_size {stack_reserved} and the "
          f"{room} bytes of RAM above the static data",
          "" if total <= stack_reserved and total <= room else f"bound {total} > reservation or room")
    print(f"firmware {elfname}: flash {flash_used} B, static RAM {ram_used} B, stack bound {total} B, "
          f"RAM with stack {ram_used + total} B")
    return 1 if check.fails else 0


if __name__ == "__main__":
    sys.exit(main())
