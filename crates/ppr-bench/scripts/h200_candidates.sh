#!/usr/bin/env bash
# The first call of a session on the lent H200: times the bench options that are built and
# tested but not yet timed, one binary, as `--projection-profile` rows, so that the
# defaults can be set before the final runs of h200.sh. Same setup as h200.sh (from the
# repository root on the device, `.gl` and `.gpu` carried, results in
# $OUT/results.tar.gz, packed again after each step). The nineteenth session's options
# (subgroup box, subgroup culling) were timed in the twentieth session's first call and
# lost (runtime.md, "The twentieth session"); the twentieth session's rows:
# - `culling on` against `culling on, prefetch` (the fused lists' first chunk of
#   candidates, source boxes and shape tests loaded before the box reduction's
#   barriers), each also as `culling on, empty, ...` (the box and the list on their own).
# Expected: about 40 s for the default scenes (6 cameras, two sizes), 50 s for the rest.
source crates/ppr-bench/scripts/h200_env.sh
ROWS=()
for row in "culling on" "culling on, prefetch" "culling on, empty" "culling on, empty, prefetch"; do
  ROWS+=(--profile-row "$row")
done
step candidates 120 $B runtime $C --projection-profile "${ROWS[@]}" --frames 10 \
  --scene demo --scene kitchen --resolution 1080p --resolution 4k --out $R/candidates
step candidates_levels 150 $B runtime $C --projection-profile "${ROWS[@]}" --frames 10 \
  --scene mirror-room-6 --scene collision-world --scene rooms-1000 --scene stairway-32 \
  --resolution 1080p --resolution 4k --out $R/candidates_levels
