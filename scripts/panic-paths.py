#!/usr/bin/env python3
"""Which panic paths are reachable from a function of an optimised binary?

Walks the call graph of `objdump -d` output (direct calls and jumps between functions)
from each root symbol and prints, for every panic entry point reached (core::panicking::*,
bounds and slice-index failures, unwrap/expect failures, the unwinder), the shortest chain
of calls that reaches it. Indirect calls (`call *%reg`, through vtables or function
pointers) cannot be followed: they are counted and listed, and make the answer a lower
bound for that root.

    python3 scripts/panic-paths.py BINARY ROOT_SUBSTRING...

Used by scripts/no-panic.sh on the `scan` build of nopanic/ (see that script).
"""
import re
import subprocess
import sys
from collections import deque

PANIC = re.compile(
    r"core(\[[0-9a-f]+\])?::panicking::|panic_bounds_check|slice_(start|end)_index_len_fail|"
    r"slice_index_order_fail|str_index_overflow_fail|unwrap_failed|expect_failed|"
    r"core(\[[0-9a-f]+\])?::option::.*failed|_Unwind_Resume|rust_begin_unwind|"
    r"std(\[[0-9a-f]+\])?::panicking::|"
    r"core::cell::panic_already|core::slice::.*fail|alloc::raw_vec::handle_error|"
    r"alloc::alloc::handle_alloc_error|capacity_overflow"
)
HEADER = re.compile(r"^[0-9a-f]+ <(.+)>:$")
TARGET = re.compile(r"\b(call|jmp|j[a-z]{1,3})\s+[0-9a-f]+ <([^+>]+)(\+0x[0-9a-f]+)?>")
INDIRECT = re.compile(r"\bcall\s+\*")


LEA = re.compile(r"\blea\s+-?0x[0-9a-f]+\(%rip\),%r(dx|si|di)\s+# ([0-9a-f]+)")


def graph(binary):
    """Calls between functions, indirect-call counts, and for each (caller, panic entry)
    the addresses loaded as the panic's `Location` argument just before the call."""
    out = subprocess.run(
        ["objdump", "-d", "--no-show-raw-insn", binary],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    edges, indirect, sites, current, recent = {}, {}, {}, None, []
    for line in out.splitlines():
        m = HEADER.match(line)
        if m:
            current, recent = m.group(1), []
            edges.setdefault(current, set())
            indirect.setdefault(current, 0)
            continue
        if current is None:
            continue
        lea = LEA.search(line)
        if lea:
            recent = (recent + [int(lea.group(2), 16)])[-2:]
        t = TARGET.search(line)
        if t and t.group(2) != current:
            callee = t.group(2).replace("@plt", "")
            edges[current].add(callee)
            sites.setdefault((current, callee), set()).update(recent)
        elif INDIRECT.search(line):
            indirect[current] += 1
    return edges, indirect, sites


def locations(binary, addresses):
    """`core::panic::Location`s (file:line:col) at the given addresses, resolving the
    file pointer through the binary's R_X86_64_RELATIVE relocations (PIE)."""
    import struct

    data = open(binary, "rb").read()
    heads = subprocess.run(["objdump", "-h", binary], capture_output=True, text=True).stdout
    sections = []
    for line in heads.splitlines():
        p = line.split()
        if len(p) >= 7 and p[0].isdigit():
            sections.append((int(p[3], 16), int(p[2], 16), int(p[5], 16)))

    def read(addr, n):
        for vma, size, off in sections:
            if vma <= addr < vma + size:
                return data[off + addr - vma : off + addr - vma + n]
        return None

    relocs = {}
    for line in subprocess.run(
        ["readelf", "-rW", binary], capture_output=True, text=True
    ).stdout.splitlines():
        p = line.split()
        if len(p) >= 4 and p[2] == "R_X86_64_RELATIVE":
            relocs[int(p[0], 16)] = int(p[-1], 16)
    found = {}
    for a in addresses:
        raw = read(a, 24)
        if raw is None or a not in relocs:
            continue
        _, length, line, col = struct.unpack("<QQII", raw)
        name = read(relocs[a], length) if 0 < length < 4096 else None
        if name and (name.endswith(b".rs")):
            found[a] = f"{name.decode(errors='replace')}:{line}:{col}"
    return found


def demangle(names):
    """Mangled symbol -> readable name (c++filt reads Rust's legacy mangling)."""
    names = sorted(names)
    out = subprocess.run(
        ["c++filt"], input="\n".join(names), capture_output=True, text=True
    ).stdout.splitlines()
    return dict(zip(names, out)) if len(out) == len(names) else {n: n for n in names}


def main():
    binary, roots = sys.argv[1], sys.argv[2:]
    edges, indirect, sites = graph(binary)
    names = demangle(set(edges) | {g for gs in edges.values() for g in gs})
    edges = {names.get(f, f): {names.get(g, g) for g in gs} for f, gs in edges.items()}
    indirect = {names.get(f, f): n for f, n in indirect.items()}
    sites = {(names.get(f, f), names.get(g, g)): a for (f, g), a in sites.items()}
    where = locations(binary, {a for s in sites.values() for a in s})
    failed = False
    for root in roots:
        starts = [f for f in edges if root in f and "NoPanic" not in f]
        if not starts:
            print(f"{root}: not found (inlined?)")
            failed = True
            continue
        for start in starts:
            parent, queue, hits, ind = {start: None}, deque([start]), [], []
            while queue:
                f = queue.popleft()
                if PANIC.search(f):
                    hits.append(f)
                    continue
                if indirect.get(f):
                    ind.append(f)
                for g in sorted(edges.get(f, ())):
                    if g not in parent:
                        parent[g] = f
                        queue.append(g)
            print(f"== {start}: {len(parent)} functions reachable, "
                  f"{len(hits)} panic entry points, {len(ind)} with indirect calls")
            for h in hits:
                chain, f = [], h
                while f is not None:
                    chain.append(f)
                    f = parent[f]
                print("   " + "\n     <- ".join(chain))
                for a in sorted(sites.get((chain[1], h), ())) if len(chain) > 1 else ():
                    if a in where:
                        print(f"     at {where[a]}")
            for f in ind:
                print(f"   indirect call(s) in {f}")
            failed |= bool(hits)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
