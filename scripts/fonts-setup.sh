#!/usr/bin/env bash
# The font the PNG plots of `host-sim bench` are drawn with (resvg shapes their text with
# system fonts): DejaVu Sans from Debian's fonts-dejavu-core. Idempotent.
set -euo pipefail
if [ -f /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ]; then
    exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
    sudo="sudo"
fi
$sudo apt-get update
$sudo apt-get install -y --no-install-recommends fonts-dejavu-core
