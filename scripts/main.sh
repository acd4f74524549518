#!/usr/bin/env bash
# The main job: install dependencies, build, then run the robot's vision on real data:
# the front end over a face set (annotated images and normalised faces in build/out/caltech),
# the detection evaluation, a classifier bank enrolled from ORL faces (build/out/robot.fsb) that
# recognises held-out faces, and the live pipeline over a real video clip (annotated video and
# track events in build/out/).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
export FACESOCIAL_DATA="${FACESOCIAL_DATA:-$(cd .. && pwd)/shared/datasets}"
fs=build/bin/facesocial
out=build/out
mkdir -p "$out"
$fs detect "$FACESOCIAL_DATA/caltech_faces1999_partial/images" --out "$out/caltech"
$fs eval detection

# A bank of ten ORL people, enrolled from images 1-5 each, recognising image 9 of two of them.
rm -f "$out/robot.fsb"
# ORL faces are already cropped: the bank is created without the elliptical mask.
$fs enrol --bank "$out/robot.fsb" --person s1 --no-mask "$FACESOCIAL_DATA"/orl/s1/{1,2,3,4,5}.pgm > /dev/null
for i in 2 3 4 5 6 7 8 9 10; do
  $fs enrol --bank "$out/robot.fsb" --person "s$i" "$FACESOCIAL_DATA"/orl/s$i/{1,2,3,4,5}.pgm > /dev/null
done
$fs train --bank "$out/robot.fsb"
$fs recognize --bank "$out/robot.fsb" --top 3 "$FACESOCIAL_DATA/orl/s3/9.pgm" "$FACESOCIAL_DATA/orl/s7/9.pgm"

# The live pipeline over a real clip: tracks, accumulated decisions, events.
$fs watch --bank "$out/robot.fsb" "$FACESOCIAL_DATA/video_hamilton/short_hamilton_clip.mp4" \
  --out "$out/hamilton_annotated.mp4" --events "$out/hamilton_events.jsonl" --quiet
echo "wrote $out/hamilton_annotated.mp4 and $out/hamilton_events.jsonl"
