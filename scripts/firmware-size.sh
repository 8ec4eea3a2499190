#!/usr/bin/env bash
# Where the firmware's bytes go: flash and static RAM per section, the largest symbols,
# the bytes by what they belong to (formatting, f64 soft-float, libm in f64 and f32, the
# start-up limit surfaces, the controller, the device and protocol, the runtime), and what
# each variant costs against the default. Reads the ELFs scripts/firmware-build.sh made;
# uses llvm-nm and llvm-size from the firmware toolchain's llvm-tools component
# (scripts/firmware-setup.sh installs it). docs/firmware-size.md keeps its output.
#
# Usage: scripts/firmware-size.sh [--top N] [VARIANT ...]   (default: every variant built)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
top=25
if [ "${1:-}" = --top ]; then
    top="$2"
    shift 2
fi
toolchain="$(sed -n 's/^channel *= *"\(.*\)"/\1/p' "$root/firmware/rust-toolchain.toml")"
bin="$(rustup run "$toolchain" rustc --print sysroot)/lib/rustlib/x86_64-unknown-linux-gnu/bin"
[ -x "$bin/llvm-nm" ] || { echo "no llvm-nm in $bin: run scripts/firmware-setup.sh" >&2; exit 1; }
variants=("$@")
if [ ${#variants[@]} -eq 0 ]; then
    for v in default prebuilt-tables soft-sqrt fast-math precompute-f64 defmt sqrt-check; do
        [ -f "$root/target/firmware/$v/softgrip-firmware.elf" ] && variants+=("$v")
    done
fi
args=()
for v in "${variants[@]}"; do
    elf="$root/target/firmware/$v/softgrip-firmware.elf"
    [ -f "$elf" ] || { echo "$elf missing: scripts/firmware-build.sh $v" >&2; exit 1; }
    args+=("$v" "$elf")
done
python3 - "$bin" "$top" "$toolchain" "${args[@]}" <<'PY'
import re, subprocess, sys

bin_dir, top, toolchain, rest = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
FLASH = (".vector_table", ".text", ".rodata", ".data")
RAM = (".data", ".bss", ".uninit")
LEGACY = [("$LT$", "<"), ("$GT$", ">"), ("$RF$", "&"), ("$BP$", "*"), ("$C$", ","),
          ("$u20$", " "), ("$u27$", "'"), ("$u5b$", "["), ("$u5d$", "]"),
          ("$u7b$", "{"), ("$u7d$", "}"), ("$u7e$", "~"), ("..", "::"), ("$", "")]

def clean(name):
    name = re.sub(r"::h[0-9a-f]{16}$", "", name)
    if name.startswith("_$LT$"):
        name = name[1:]
    for a, b in LEGACY:
        name = name.replace(a, b)
    return name

def group(name):
    n = name
    if re.search(r"core::fmt|flt2dec|bignum|Formatter|fmt::Display|fmt::Debug|fmt::Write"
                 r"|as core::fmt|Truncating|CACHED_POW10|DEC_DIGITS_LUT", n):
        return "formatting (core::fmt)"
    if re.search(r"__(add|sub|mul|div|cmp|eq|ne|lt|le|gt|ge|un|extendsf|truncdf|fix|float)\w*df|"
                 r"__aeabi_d|compiler_builtins::float", n):
        return "f64 soft-float (compiler_builtins)"
    m = re.match(r"libm::math::(?:[\w:]*::)?(\w+)$", n)
    if n.startswith("libm::"):
        last = n.rsplit("::", 1)[-1]
        return "libm, f32" if last.endswith("f") and last not in ("modf",) else "libm, f64"
    if re.search(r"softgrip::(fls|pressure|quadrature|skew|contact|partial_slip)|capacity::build"
                 r"|inscribed_ellipse|InscribedEllipse", n):
        return "limit surfaces (start-up precomputation)"
    if "softgrip::controller" in n:
        return "controller (config, tables, tick)"
    if re.search(r"softgrip::(device|protocol)|postcard|serde|cobs|crc|heapless|embedded_io", n):
        return "device loop and protocol"
    if re.search(r"softgrip_firmware|cortex_m|__aeabi_mem|compiler_builtins::mem|memcpy|memset"
                 r"|__INTERRUPTS|__EXCEPTIONS|__RESET_VECTOR|Reset|HardFault|DefaultHandler"
                 r"|__pre_init|u64_div_rem|__aeabi_ul|__udiv|__aeabi_ui|compiler_builtins::int", n):
        return "runtime and integer helpers"
    if n.startswith(".L") or n.startswith("anon"):
        return "anonymous constants"
    return "other"

def sections(elf):
    out = subprocess.run([f"{bin_dir}/llvm-size", "-A", elf], check=True,
                         capture_output=True, text=True).stdout
    secs = {}
    for line in out.splitlines():
        p = line.split()
        if len(p) >= 3 and p[0].startswith(".") and p[1].isdigit():
            secs[p[0]] = int(p[1])
    return secs

def symbols(elf):
    out = subprocess.run([f"{bin_dir}/llvm-nm", "-S", "--size-sort", "-C", "--radix=d", elf],
                         check=True, capture_output=True, text=True).stdout
    syms = []
    for line in out.splitlines():
        p = line.split(None, 3)
        if len(p) == 4 and p[2].lower() in "tdrb":
            syms.append((int(p[1]), p[2], clean(p[3])))
    return syms

print(f"Firmware sizes (scripts/firmware-size.sh; rustc {toolchain}, profile `firmware`)\n")
results = {}
for v, elf in zip(rest[0::2], rest[1::2]):
    secs, syms = sections(elf), symbols(elf)
    flash = sum(secs.get(s, 0) for s in FLASH)
    ram = sum(secs.get(s, 0) for s in RAM)
    groups = {}
    for size, kind, name in syms:
        if kind.lower() in "tr":
            g = group(name)
            groups[g] = groups.get(g, 0) + size
    results[v] = (flash, ram, groups)
    print(f"## {v}\n")
    print("| section | bytes | in |\n| --- | ---: | --- |")
    for s in (".vector_table", ".text", ".rodata", ".data", ".bss", ".uninit"):
        where = "flash + RAM" if s == ".data" else ("flash" if s in FLASH else "RAM")
        print(f"| `{s}` | {secs.get(s, 0)} | {where} |")
    print(f"| **flash** | **{flash}** | |\n| **static RAM** | **{ram}** | (+ the stack, "
          "measured by painting: host-sim/tests/qemu_link.rs) |\n")
    attributed = sum(groups.values())
    print("| what | flash bytes | share |\n| --- | ---: | ---: |")
    for g, n in sorted(groups.items(), key=lambda kv: -kv[1]):
        print(f"| {g} | {n} | {100 * n / flash:.1f} % |")
    print(f"| (padding, unsized) | {flash - attributed} | {100 * (flash - attributed) / flash:.1f} % |\n")
    print(f"Largest {top} symbols:\n\n| bytes | symbol |\n| ---: | --- |")
    for size, kind, name in sorted(syms, key=lambda s: -s[0])[:top]:
        print(f"| {size} | `{name[:110]}` |")
    print()
if "default" in results and len(results) > 1:
    base_flash, base_ram, base_groups = results["default"]
    print("## Each variant against the default\n")
    print("| variant | flash | Δ flash | static RAM | largest changes |\n| --- | ---: | ---: | ---: | --- |")
    for v, (flash, ram, groups) in results.items():
        if v == "default":
            continue
        keys = set(groups) | set(base_groups)
        deltas = sorted(((groups.get(k, 0) - base_groups.get(k, 0), k) for k in keys),
                        key=lambda d: -abs(d[0]))
        changes = "; ".join(f"{k} {d:+d}" for d, k in deltas[:3] if d)
        print(f"| {v} | {flash} | {flash - base_flash:+d} | {ram} | {changes} |")
PY
