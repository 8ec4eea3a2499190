#!/usr/bin/env bash
# Sets up the Cortex-M4F toolchain and QEMU on a fresh machine (see docs/firmware.md).
# Safe to run again: each step checks whether it is already done.
#
# - The firmware's pinned stable toolchain (firmware/rust-toolchain.toml) with rustup's
#   prebuilt standard library for thumbv7em-none-eabihf: a plain stable build.
# - Only if rustup cannot install that (no network to its servers): Debian's rustc-web,
#   cargo-web and rust-web-src, for scripts/firmware-build.sh's build-std fallback (which
#   needs RUSTC_BOOTSTRAP to build `core`). They install /usr/bin/rustc and /usr/bin/cargo;
#   rustup's ~/.cargo/bin stays first on PATH, so host builds are unchanged.
# - qemu-system-arm, downloaded and unpacked into .firmware/qemu (never apt-installed: that
#   would remove the machine's qemu-utils).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
target=thumbv7em-none-eabihf
toolchain="$(sed -n 's/^channel *= *"\(.*\)"/\1/p' "$root/firmware/rust-toolchain.toml")"
apt_updated=0
apt_update() {
    if [ "$apt_updated" = 0 ]; then
        apt-get update -qq
        apt_updated=1
    fi
}
has_target() {
    local dir
    dir="$(rustup run "$toolchain" rustc --print target-libdir --target "$target" 2>/dev/null)" \
        && ls "$dir"/libcore-*.rlib >/dev/null 2>&1
}

if ! has_target; then
    rustup toolchain install "$toolchain" --profile minimal --component clippy,llvm-tools \
        --target "$target" >&2 \
        || rustup target add --toolchain "$toolchain" "$target" >&2 || true
fi
if has_target; then
    echo "rustc for the target: $(rustup run "$toolchain" rustc --version) (rustup, $target)"
else
    echo "rustup could not install $toolchain for $target: Debian's rustc-web for build-std" >&2
    if ! [ -x /usr/bin/rustc ] || ! /usr/bin/rustc --print sysroot >/dev/null 2>&1 \
        || ! [ -d "$(/usr/bin/rustc --print sysroot)/lib/rustlib/src" ]; then
        apt_update
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
            rustc-web cargo-web rust-web-src >/dev/null
    fi
    echo "rustc for the target: $(/usr/bin/rustc --version) (build-std fallback)"
fi

qemu_dir="$root/.firmware/qemu"
if ! [ -x "$qemu_dir/usr/bin/qemu-system-arm" ]; then
    apt_update
    tmp="$(mktemp -d)"
    (
        cd "$tmp"
        apt-get download -qq qemu-system-arm libfdt1 libcapstone4 libpmem1 librdmacm1 \
            libibverbs1 libslirp0 libvdeplug2 libndctl6 libdaxctl1 libnl-3-200 \
            libnl-route-3-200 >/dev/null
    )
    mkdir -p "$qemu_dir"
    for deb in "$tmp"/*.deb; do
        dpkg-deb -x "$deb" "$qemu_dir"
    done
    rm -rf "$tmp"
fi

echo "qemu: $(LD_LIBRARY_PATH="$qemu_dir/usr/lib/x86_64-linux-gnu:$qemu_dir/lib/x86_64-linux-gnu" \
    "$qemu_dir/usr/bin/qemu-system-arm" --version | head -1)"
