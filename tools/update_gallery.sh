#!/usr/bin/env bash
# Render every lab part afresh with glslcheck's CPU (NumPy) backend into docs/gallery/, the
# images lab_shaders/README.md shows. `make run` calls this; `glslcheck verify` (also in
# `make run`) shows these CPU renders agree with OpenGL.
set -euo pipefail
cd "$(dirname "$0")/.."
GLSLCHECK="${GLSLCHECK:-.venv/bin/glslcheck}"
mkdir -p docs/gallery
for part in lab_shaders/*/; do
    name="$(basename "$part")"
    "$GLSLCHECK" render "$part" --size 800x450 --time 1.0 -o "docs/gallery/$name.png"
    echo "rendered docs/gallery/$name.png"
done
