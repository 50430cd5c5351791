#!/usr/bin/env bash
# The thirty-second session's last call: the head (.gpu/ppr-bench.gz, 7a25077: the glossy
# taps, the layer pass over its tiles and beside the reflection without a barrier), its
# profile and compare (the numbers of record's suites). Same setup as h200.sh.
# Expected: 200 + 240 s.
bash crates/ppr-bench/scripts/h200.sh profile compare
