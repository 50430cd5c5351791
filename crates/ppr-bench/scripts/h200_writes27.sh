#!/usr/bin/env bash
# The twenty-seventh session's two projection options, built and tested but not yet timed
# (no device was left): batched writes and the pending plane reloaded, each against the
# head in the same call, per pass and as whole frames, on the demo, the kitchen, the rooms
# and collision-world; then the driver's register counts of both (pipeline-stats).
# Run from the repository root on the lent GPU with `.gl` and `.gpu` carried.
source crates/ppr-bench/scripts/h200_env.sh
ROWS=(--profile-row "reflection own pass" --profile-row "frame span"
  --profile-row "frame span, batched writes" --profile-row "reflection own pass, batched writes"
  --profile-row "frame span, reload pending" --profile-row "reflection own pass, reload pending"
  --profile-row "frame span, batched writes, reload pending")
step runtime 210 $B runtime $C --projection-profile --frames 20 "${ROWS[@]}" --out $R/runtime
step gen 110 $B runtime $C --projection-profile --frames 10 --scene rooms-1000 --scene collision-world --resolution 4k "${ROWS[@]}" --out $R/gen
step stats 60 $B pipeline-stats $C --projection-variants --out $R/stats
