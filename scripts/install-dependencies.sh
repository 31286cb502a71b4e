#!/bin/bash
# Installs what tmfdem needs on Debian bookworm (as root), or prints the exact
# apt command to run (when not root). Idempotent: installs only what is
# missing.
set -euo pipefail
packages=(build-essential cmake libdeal.ii-dev libeigen3-dev gmsh openmpi-bin libgtest-dev
          python3 python3-numpy python3-matplotlib python3-scipy python3-meshio
          paraview python3-paraview xvfb xauth)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "[tmfdem] all dependencies are installed"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "[tmfdem] missing packages: ${missing[*]}" >&2
  echo "[tmfdem] run as root:  apt-get update && apt-get install -y --no-install-recommends ${missing[*]}" >&2
  exit 1
fi
echo "[tmfdem] installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q --no-install-recommends "${missing[@]}"
