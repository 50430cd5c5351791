#!/usr/bin/env bash
# The first call of a session on the lent H200: times the bench options that are built and
# tested but not yet timed (docs/perf/runtime.md, "The nineteenth session"), one binary,
# as `--projection-profile` rows, so that the defaults can be set before the final runs of
# h200.sh. Same setup as h200.sh (from the repository root on the device, `.gl` and `.gpu`
# carried, results in $OUT/results.tar.gz, packed again after each step). Rows:
# - `culling on` against `culling on, subgroup box` (the fused lists' box through one slot
#   per subgroup and one barrier) and `culling on, subgroup box atomics` (per subgroup
#   first, then the workgroup's atomics), each also as `culling on, empty, ...` (what the
#   box and the list cost on their own);
# - `subgroup culling only` (no tile lists; each subgroup culls its candidates against its
#   own box and flags those whose pyramid holds it) with and without its inside flags, and
#   `... tests only` against `culling on, tests only`; and `subgroup culling on` (the
#   block lists culled again per subgroup, with the subgroup's inside flags: the rooms'
#   10-30 candidates a block facing every way).
# Expected: about 100 s for the default scenes (6 cameras, two sizes), 150 s for the rest.
source crates/ppr-bench/scripts/h200_env.sh
ROWS=()
for row in "culling on" "culling on, subgroup box" "culling on, subgroup box atomics" \
    "culling on, empty" "culling on, empty, subgroup box" "culling on, empty, subgroup box atomics" \
    "culling on, tests only" "subgroup culling only" "subgroup culling only, no inside entries" \
    "subgroup culling only, tests only" "subgroup culling on"; do
  ROWS+=(--profile-row "$row")
done
step candidates 200 $B runtime $C --projection-profile "${ROWS[@]}" --frames 10 \
  --scene demo --scene kitchen --resolution 1080p --resolution 4k --out $R/candidates
step candidates_levels 260 $B runtime $C --projection-profile "${ROWS[@]}" --frames 10 \
  --scene mirror-room-6 --scene collision-world --scene rooms-1000 --scene rooms-16 \
  --scene stairway-8 --scene stairway-16 --scene stairway-32 \
  --resolution 1080p --resolution 4k --out $R/candidates_levels
