#!/bin/bash
# The README's first command: install what is missing, build Release, run the
# showcase case and draw its result.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-dependencies.sh
bash scripts/build.sh Release
case=prm/thick_cylinder-continuum.prm
out=output/showcase
./build-release/tmfdem "$case" --set "Output/Directory=$out"
/usr/bin/python3 scripts/plot_vtu.py "$out/solution.pvd" "$out/showcase.png" \
  --field T --label "T [C]" --edges \
  --title "hollow cylinder, steady temperature on the adaptive mesh"
/usr/bin/python3 scripts/plot_case.py thick_cylinder-continuum "$out" "$out/radial.png"
echo "[tmfdem] showcase written to $out/: solution.pvd (ParaView), lines.csv, summary.json, showcase.png, radial.png"
