#!/usr/bin/env bash
# Installs the system packages that the live checks of scripts/test.sh need, where they are
# missing: a browser (`chromium`, for the 3D replay page), OpenBLAS with gfortran and pkg-config
# (the physically consistent identification, feature `sdp`), and Python's venv module. The one
# home of this list: scripts/test.sh runs it first, and .ci/run runs scripts/test.sh, so what the
# README's test command needs is what CI installs.
#
# It uses apt-get as root (as on these machines). Without root or apt-get it installs nothing,
# names the packages and the command to run, and exits 3.
set -euo pipefail

missing=()
command -v chromium >/dev/null 2>&1 || missing+=(chromium)
if ! command -v pkg-config >/dev/null 2>&1; then
    missing+=(pkg-config libopenblas-dev)
elif ! pkg-config --exists openblas 2>/dev/null; then
    missing+=(libopenblas-dev)
fi
# clarabel's OpenBLAS link also asks for libgfortran of the C compiler's version
if command -v gcc >/dev/null 2>&1 && ! gcc -print-file-name=libgfortran.so | grep -q /; then
    missing+=("libgfortran-$(gcc -dumpversion | cut -d. -f1)-dev")
fi
python3 -c "import ensurepip, venv" 2>/dev/null || missing+=(python3-venv)

if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "error: the live checks need these system packages: ${missing[*]}" >&2
    echo "       install them (Debian/Ubuntu: sudo apt-get install ${missing[*]}), then run" \
        "bash scripts/test.sh again; cargo test --workspace alone needs none of them" >&2
    exit 3
fi
echo "installing the system packages the live checks need: ${missing[*]} (apt-get)"
start=$(date +%s)
apt-get update -qq
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
echo "installed in $(($(date +%s) - start)) s"
