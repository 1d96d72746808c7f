#!/usr/bin/env bash
# Regenerate the figures of docs/guide.md with the commands the guide shows (an installed
# `groove` on PATH). Run from anywhere: docs/figures/make.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
groove trace -k 0.5 2 20 --out out/
groove plot out/boundaries_k2.csv -o k2.png --deg
groove map -k 2 -o map_k2.png
groove atlas --k-min 0.1 --k-max 100 --out atlas/
groove compliance --out compliance/
cp out/boundaries_k0.5_k2_k20.png "$here/trace_k0.5_k2_k20.png"
cp k2.png "$here/plot_k2_deg.png"
cp map_k2.png "$here/map_k2.png"
cp atlas/atlas.png "$here/atlas_k0.1_100.png"
cp compliance/compliance.png "$here/compliance.png"
