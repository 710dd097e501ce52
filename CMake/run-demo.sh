#!/bin/sh
# The main job end to end on the bundled default data (`make demo`):
#   1. segment the airway of the real CT (InVesalius' Cranium.inv3),
#   2. simulate a 30-frame endoscope sequence in it (the virtual endoscope,
#      with a tracker recording), the scope held upright within 10 degrees,
#   3. register the video to the CT with `vimlop register`: contours, SfM,
#      tracker scale, multi-start from canonical poses along the airway,
#      registered video and report,
#   4. print the camera errors against the simulation's ground truth.
# Usage: run-demo.sh BUILD_DIR CT OUT_DIR [SEED]
set -eu
build=$1
ct=$2
out=$3
seed=${4:-1}
root=$(cd "$(dirname "$0")/.." && pwd)
vimlop="$build/bin/vimlop"
display="$root/CMake/run-with-display.sh"
if [ ! -f "$ct" ]; then
  echo "demo: error: '$ct' is missing (Debian package invesalius-examples)" >&2
  exit 1
fi
start=$(date +%s)
mkdir -p "$out"
echo "demo: 1/3 airway of $ct"
"$vimlop" segment --ct "$ct" --out "$out/airway.vtp"
echo "demo: 2/3 simulated endoscope sequence (seed $seed)"
rm -rf "$out/sim"
"$display" "$vimlop" simulate --mesh "$out/airway.vtp" --frames 30 --seed "$seed" --upright-deg 10 \
  --out "$out/sim" 2>/dev/null
echo "demo: 3/3 registration from canonical poses"
status=0
"$display" "$vimlop" register --mesh "$out/airway.vtp" --frames "$out/sim/frames" \
  --intrinsics "$out/sim/intrinsics.yaml" --tracker "$out/sim/tracker.csv" --fps 30 \
  --truth "$out/sim/truth/poses.json" --init canonical --out "$out/result" --force || status=$?
if [ "$status" -ne 0 ] && [ "$status" -ne 3 ]; then
  exit "$status"
fi
echo "demo: report in $out/result/report/index.html, registered video in $out/result/registered-video.avi"
echo "demo: done in $(( $(date +%s) - start )) s"
exit "$status"
