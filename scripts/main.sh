#!/usr/bin/env bash
# The main job: install dependencies, build, then run the vision front end over a real face set
# (detections printed, annotated images and normalised faces written to build/out/) and the
# detection evaluation.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
export FACESOCIAL_DATA="${FACESOCIAL_DATA:-$(cd .. && pwd)/shared/datasets}"
build/bin/facesocial detect "$FACESOCIAL_DATA/caltech_faces1999_partial/images" --out build/out/caltech
build/bin/facesocial eval detection
