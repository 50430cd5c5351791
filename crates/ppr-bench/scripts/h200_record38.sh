#!/usr/bin/env bash
# The thirty-eighth session's calls (same setup: `bash tools/pack_gpu.sh`, carry .gl and
# .gpu). Steps:
#   profile, generated, collision, compare: h200_record36.sh's record steps, unchanged;
#   fixed: the rows that take the frame's fixed cost apart, on the demo and the kitchen
#     (each pass timed on its own with the projection empty, testing only, or not writing;
#     the reflection pass empty, without glossy, mirrors only; the classification on its
#     own; the whole frame with the projection empty), about 60 s;
#   fixed4k: the same at 4K only, 10 frames;
#   stdiag: the same rows on the stairway at 1, 1 000 and 10 000 treads, about 40 s.
#
#   bash crates/ppr-bench/scripts/h200_record38.sh fixed stdiag profile generated collision  # ~560 s
#   bash crates/ppr-bench/scripts/h200_record38.sh compare                                   # ~420 s
STEPS=" $* "
want() { [[ "$STEPS" == *" $1 "* ]]; }
source crates/ppr-bench/scripts/h200_env.sh
ROWS=()
for row in "empty" "empty, reflection own pass" "tests only, reflection own pass" \
    "no write, reflection own pass" "no atomic" "no atomic, reflection own pass" "reflection own pass" "reflection: empty, reflection own pass" \
    "reflection: no glossy, reflection own pass" "reflection: mirrors, reflection own pass" \
    "classify own pass" "frame span" "frame span, empty" "frame span, classify own pass"; do
  ROWS+=(--profile-row "$row")
done
want fixed && step fixed 150 $B runtime $C --projection-profile "${ROWS[@]}" --frames 20 --scene demo --scene kitchen --out $R/fixed
# fixed4k: the same at 4K only, 10 frames (about 25 s), when little device time is left.
want fixed4k && step fixed4k 100 $B runtime $C --projection-profile "${ROWS[@]}" --frames 10 --scene demo --scene kitchen --resolution 4k --out $R/fixed4k
want stdiag && step stdiag 120 $B runtime $C --projection-profile "${ROWS[@]}" --frames 10 --scene stairway-1 --scene stairway-1000 --scene stairway-10000 --resolution 4k --out $R/stdiag
REST=""
for s in compare collision profile generated; do want $s && REST="$REST $s"; done
if [ -n "$REST" ]; then bash crates/ppr-bench/scripts/h200_record36.sh $REST; fi
