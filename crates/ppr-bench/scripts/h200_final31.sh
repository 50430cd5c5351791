#!/usr/bin/env bash
# The thirty-first session's last call: the layer pass with its depth loaded first
# (.gpu/ppr-bench-l.gz) against the head (.gpu/ppr-bench.gz, 43c329b: the layer tiles and
# the indirect reflection's loads), the demo's frames with the layer rows, in the order
# head, l, l, head; then the head's profile and compare (the numbers of record's suites).
# Same setup as h200.sh. Expected: 4 x 15 + 190 + 255 s.
source crates/ppr-bench/scripts/h200_env.sh
gunzip -c .gpu/ppr-bench-l.gz > .gpu/ppr-bench-l && chmod +x .gpu/ppr-bench-l
ROWS=()
for row in "layers: own pass" "layers: after reflection" "frame span"; do ROWS+=(--profile-row "$row"); done
for run in h1:$B l1:.gpu/ppr-bench-l l2:.gpu/ppr-bench-l h2:$B; do
  step ab_${run%%:*} 60 ${run#*:} runtime $C --projection-profile "${ROWS[@]}" --scene demo --frames 20 --out $R/ab_${run%%:*}
done
bash crates/ppr-bench/scripts/h200.sh profile compare
