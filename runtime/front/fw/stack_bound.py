#!/usr/bin/env python3
"""Static stack bound of a firmware ELF: the deepest call path from _start, in bytes.

Promise: the bound is never below what the program can use, given the stated assumptions.
  - Our code (runtime, front end, model): each function's frame is what gcc's -fstack-usage wrote
    (OBJ/*.su, every entry must be "static"), its callees are gcc's call graph (-fcallgraph-info=su,
    OBJ/*.ci). Calls the compiler inlined are inside the caller's frame.
  - Library code (picolibc, libgcc) has no .su files: its frames are read from the ELF's disassembly
    (push/stmdb, vpush, sub sp), its callees from its bl/blx/b.w to other functions.
  - Recursion: the renderer's walk (visit, visit_inside in octree_render.c) recurses once per octree level
    and never deeper than the drawn depth D (octree_render.h); every path may enter recursive functions at
    most D times in all. Any other cycle is an error.
  - Indirect calls: in our code only the renderer's abort callback (mc_octree_render's `abort`), which the
    firmware passes as NULL: counted as 0, stated in the output. In library code (stdio's FILE
    put/get callbacks) each counts as the deepest of the library's semihosting character functions.
  - Interrupts: the firmware enables none.
Usage: stack_bound.py ELF OBJDIR DEPTH [--verbose]   prints "stack bound N bytes" and the path.
"""
import glob
import os
import re
import subprocess
import sys

OBJDUMP = "arm-none-eabi-objdump"
NM = "arm-none-eabi-nm"


def parse_su(objdir):
    """{function name as in the .ci titles' last part: bytes} from the .su files."""
    frames = {}
    for su in glob.glob(os.path.join(objdir, "*.su")):
        for line in open(su):
            line = line.rstrip("\n")
            if not line:
                continue
            loc, size, kind = line.split("\t")
            if kind != "static":
                raise SystemExit(f"stack_bound: {su}: {loc} has a {kind} frame: no static bound")
            file, _, _, func = loc.rsplit(":", 3)
            frames[(file, func)] = int(size)
    return frames


NODE = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
EDGE = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')


def parse_ci(objdir):
    """Nodes with a frame {title: bytes} and edges {title: set(titles)} from the .ci files."""
    nodes, edges = {}, {}
    for ci in glob.glob(os.path.join(objdir, "*.ci")):
        for line in open(ci):
            m = NODE.match(line)
            if m:
                title, label = m.groups()
                mm = re.search(r"\\n(\d+) bytes \((\w+)\)", label)
                if mm:
                    if mm.group(2) != "static":
                        raise SystemExit(f"stack_bound: {ci}: {title}: {mm.group(2)} frame: no static bound")
                    nodes[title] = int(mm.group(1))
                continue
            m = EDGE.match(line)
            if m:
                edges.setdefault(m.group(1), set()).add(m.group(2))
    return nodes, edges


INSN = re.compile(r"^\s*[0-9a-f]+:\s+(?:[0-9a-f]{4}\s?){1,2}\s+(\S+)\s*(.*)$")
FUNC = re.compile(r"^[0-9a-f]+ <([^>]+)>:$")
TARGET = re.compile(r"^[0-9a-f]+ <([^>+]+)>")


def reglist_bytes(ops):
    m = re.search(r"\{([^}]*)\}", ops)
    if not m:
        return 0
    n = 0
    for part in m.group(1).split(","):
        part = part.strip()
        r = re.match(r"([rds])(\d+)-[rds]?(\d+)$", part)
        if r:
            k = int(r.group(3)) - int(r.group(2)) + 1
            n += k * (8 if r.group(1) == "d" else 4)
        elif part.startswith("d"):
            n += 8
        elif part:
            n += 4
    return n


def parse_disassembly(elf):
    """{function: (frame bytes, set(callees), indirect?, dynamic?)} for every function in the ELF."""
    out = subprocess.run([OBJDUMP, "-d", "--no-show-raw-insn", elf], capture_output=True, text=True, check=True).stdout
    funcs, cur = {}, None
    for line in out.splitlines():
        m = FUNC.match(line)
        if m:
            cur = m.group(1)
            funcs[cur] = [0, set(), False, False]
            continue
        if cur is None:
            continue
        m = re.match(r"^\s*[0-9a-f]+:\s+(\S+)\s*(.*)$", line)
        if not m:
            continue
        op, ops = m.group(1), m.group(2)
        f = funcs[cur]
        base = op.split(".")[0]
        if base == "push" or (base == "stmdb" and ops.startswith("sp!")) or base == "vpush":
            f[0] += reglist_bytes(ops)
        elif base in ("sub", "subw") and re.match(r"sp,\s*(sp,\s*)?#", ops):
            f[0] += int(re.search(r"#(\d+)", ops).group(1))
        elif base in ("sub", "subw") and re.match(r"sp,\s*(sp,\s*)?r", ops):
            f[3] = True
        elif base in ("bl", "blx", "b") and ops:
            t = TARGET.match(ops)
            if t and t.group(1) != cur:
                if base != "b" or True:
                    f[1].add(t.group(1))
            elif base == "blx" and not t:
                f[2] = True
        elif base == "bx" and not ops.startswith("lr"):
            f[2] = True
    return {k: tuple(v) for k, v in funcs.items()}


def strip_clone(name):
    return re.sub(r"\.(constprop|isra|part|cold)\.\d+.*$", "", name)


def bound(elf, objdir, depth, verbose=False):
    su = parse_su(objdir)
    ci_nodes, ci_edges = parse_ci(objdir)
    dis = parse_disassembly(elf)
    # our functions by plain name (for library -> our code calls such as _start -> main)
    ours_by_name = {}
    for title in ci_nodes:
        ours_by_name.setdefault(strip_clone(title.split(":")[-1]), title)
    indirect_notes = set()
    lib_indirect = max((dis[n][0] for n in dis if n.startswith("sys_semihost_putc") or n.startswith("sys_semihost_getc")),
                       default=0)

    def callees(node):
        kind, name = node
        if kind == "ci":
            for t in sorted(ci_edges.get(name, ())):
                if t == "__indirect_call":
                    indirect_notes.add(name)
                    continue
                if t in ci_nodes:
                    yield ("ci", t)
                elif t in dis or strip_clone(t) in dis:
                    yield ("lib", t if t in dis else strip_clone(t))
                elif t.split(":")[-1] in ours_by_name:
                    yield ("ci", ours_by_name[t.split(":")[-1]])
                else:
                    # declared but not linked (removed by --gc-sections or never called): no frame
                    pass
        else:
            frame, calls, indirect, dynamic = dis[name]
            for t in sorted(calls):
                plain = strip_clone(t)
                if plain in ours_by_name:
                    yield ("ci", ours_by_name[plain])
                elif t in dis:
                    yield ("lib", t)

    def frame(node):
        kind, name = node
        if kind == "ci":
            return ci_nodes[name]
        f, _, indirect, dynamic = dis[name]
        if dynamic:
            raise SystemExit(f"stack_bound: {name} moves sp by a register: no static bound")
        return f + (lib_indirect if indirect else 0)

    # recursive nodes: those on a cycle
    graph = {}
    todo = [("lib", "_start")]
    while todo:
        n = todo.pop()
        if n in graph:
            continue
        graph[n] = list(callees(n))
        todo.extend(graph[n])
    index, low, onstack, stack, sccs, counter = {}, {}, set(), [], [], [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        onstack.add(v)
        for w in graph[v]:
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in onstack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                onstack.discard(w)
                comp.append(w)
                if w == v:
                    break
            sccs.append(comp)

    sys.setrecursionlimit(10000)
    for v in list(graph):
        if v not in index:
            strong(v)
    recursive = set()
    for comp in sccs:
        if len(comp) > 1 or comp[0] in graph[comp[0]]:
            names = {n[1].split(":")[-1] for n in comp}
            if not names <= {"visit", "visit_inside"}:
                raise SystemExit(f"stack_bound: unexpected recursion among {sorted(names)}")
            recursive.update(comp)

    memo = {}

    def deepest(node, budget):
        key = (node, budget)
        if key in memo:
            return memo[key]
        best, best_path = 0, []
        for c in graph[node]:
            b = budget
            if c in recursive:
                if b == 0:
                    continue
                b -= 1
            d, p = deepest(c, b)
            if d > best:
                best, best_path = d, p
        res = (frame(node) + best, [node] + best_path)
        memo[key] = res
        return res

    total, path = deepest(("lib", "_start"), depth)
    return total, path, sorted(indirect_notes)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    elf, objdir, depth = args[0], args[1], int(args[2])
    total, path, indirect = bound(elf, objdir, depth)
    print(f"stack bound {total} bytes (from _start, renderer recursion at most {depth} frames)")
    for kind, name in path:
        print(f"  {name.split(':')[-1]} ({'-fstack-usage' if kind == 'ci' else 'disassembly'})")
    if indirect:
        print("  indirect calls counted as 0 (the abort callback, NULL in the firmware): "
              + ", ".join(n.split(":")[-1] for n in indirect))
    return 0


if __name__ == "__main__":
    sys.exit(main())
