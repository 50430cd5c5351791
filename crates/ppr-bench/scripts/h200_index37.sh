#!/usr/bin/env bash
# What the stairway's frame is made of with and without the trees' offset index (the
# thirty-seventh session's third call, about 60 s): `runtime --projection-profile` rows on
# the 1 000- and 10 000-tread stairways at 4K: the default frame, `no offset index`, the
# walk or index and the members' tests alone (`tests only, offset index`, `tests only, no
# offset index`), `no write`, `path blockers off`. Same setup as h200.sh.
source crates/ppr-bench/scripts/h200_env.sh
ROWS=()
for row in "no offset index" "tests only, offset index" "tests only, no offset index" "no write" "path blockers off" "frame span"; do
  ROWS+=(--profile-row "$row")
done
step index_profile 200 $B runtime $C --projection-profile "${ROWS[@]}" --frames 10 --scene stairway-1 --scene stairway-1000 --scene stairway-10000 --resolution 4k --out $R/index_profile
