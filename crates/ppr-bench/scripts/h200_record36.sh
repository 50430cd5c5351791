#!/usr/bin/env bash
# The record issue 13 closes on (written in the thirty-sixth session, not yet run): one
# binary of the final code (.gpu/ppr-bench.gz, its commit in .gpu/BUILT_FROM) measures
# every suite the goals read, on the lent H200 (or whatever card the call gets: name it).
# Same setup as h200.sh (`bash tools/pack_gpu.sh` builds and packs .gl and .gpu). Two calls
# of under 600 s each:
#
#   bash crates/ppr-bench/scripts/h200_record36.sh compare collision     # ~330 + 80 s
#   bash crates/ppr-bench/scripts/h200_record36.sh profile generated     # ~200 + 150 s
#   (scalecounts, ~100 s, when the device time left allows: scaling.md's full table)
#
# Then, on the development machine, from the unpacked results:
#
#   ppr-bench goals --runtime results/profile --runtime results/generated \
#     --compare results/compare --compare results/collision \
#     --baseline-compare docs/perf/comparison_34_h100.csv --out /tmp/goals.md
#
# which judges every goal of the issue from these files (the compare, collision and
# profile steps are h200_record34.sh's and h200.sh's; `generated` is new: the scaling
# families at 1 to 10 000 shapes as runtime scenes, each the default plan's frame).
STEPS=" $* "
want() { [[ "$STEPS" == *" $1 "* ]]; }
if want compare || want collision; then
  bash crates/ppr-bench/scripts/h200_record34.sh $(want compare && echo compare) $(want collision && echo collision)
fi
if want profile || want scalecounts; then
  bash crates/ppr-bench/scripts/h200.sh $(want profile && echo profile) $(want scalecounts && echo scalecounts)
fi
if want generated; then
  source crates/ppr-bench/scripts/h200_env.sh
  G=()
  for family in stairway rooms tiled-floor facade; do
    for count in 1 10 100 1000 10000; do G+=(--scene "$family-$count"); done
  done
  step generated 280 $B runtime $C "${G[@]}" --resolution 4k --frames 10 --out $R/generated
fi
