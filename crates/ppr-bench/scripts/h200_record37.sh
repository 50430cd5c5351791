#!/usr/bin/env bash
# The thirty-seventh session's record: h200_record36.sh's steps (the record issue 13 closes
# on: compare, collision, profile, generated) with the trees' offset index on by default,
# plus `index`: the scaling suite's stairway at 1, 100, 300, 1 000 and 10 000 treads with its
# variants, `parallel trees` (with the index) beside `trees, no offset index` (the walk
# alone; below 768 treads the default plan has no tree: where a tree with an index starts
# to pay), about 60 s. Same setup (`bash tools/pack_gpu.sh`); two calls of under 600 s:
#
#   bash crates/ppr-bench/scripts/h200_record37.sh compare collision        # ~330 + 80 s
#   bash crates/ppr-bench/scripts/h200_record37.sh index profile generated  # ~60 + 200 + 150 s
STEPS=" $* "
want() { [[ "$STEPS" == *" $1 "* ]]; }
if want index; then
  source crates/ppr-bench/scripts/h200_env.sh
  step index 120 $B scaling $C --out $R/index --family stairway --counts 1,100,300,1000,10000 --threshold-counts 8 --coverages 0.3 --frames 10
fi
REST=""
for s in compare collision profile generated scalecounts; do want $s && REST="$REST $s"; done
if [ -n "$REST" ]; then bash crates/ppr-bench/scripts/h200_record36.sh $REST; fi
