#!/usr/bin/env bash
# What ran on the lent H200 for docs/perf/runtime.md, scaling.md and comparison.md (recipe:
# shared/gpu/README.md). From the repository root on the device, with `.gl` (loader debs) and
# `.gpu` (the stripped release binary `.gpu/ppr-bench` and the shared scenes under
# `.gpu/scenes/`) carried; results go to $OUT/results.tar.gz (only 8 files come back from
# the device, so everything travels as one archive). About 700 s of device time in all (2026-12-03, sixth session: profile 81 s, scaling 132, collision 80, compare 205, rooms 173, bounces 67; seventh session, one call: profile 94, compare 216, scaling 151, the rest not re-run; eighth session, two calls: profile 101, collision 96, scaling 193 with two more variants, then profile 95 and compare 271 with four more techniques; ninth session, two calls: profile 103, compare 197, collision 77; scaling 142, rooms 161, bounces 66; tenth session: profile 95, scaling 138, generated levels' profile 70, the rest not re-run; eleventh session, with the settling warm-up and the faster of two runs: compare 260, profile 107, generated levels' profile 87 for three scenes, scaling 160 (the last two before the faster-of-two rule), the rest not re-run; twelfth session, four calls: the generated levels' profile 115-122 s for three scenes (92 for the two stairways), scaling 259-264 with its two rounds, collision 77, the default scenes' profile at 4K only 109; thirteenth session, with `runtime`'s two rounds: profile 200-220, generated levels' profile 147-172, compare 267, rooms 190, collision 73; fourteenth session, three calls: profile 199, generated levels' profile 147, collision 76; compare 247, scaling 259; rooms 209; fifteenth session, A/B calls with `runtime --profile-row` of 10-70 s a step, glossy `runtime --glossy --stereo` 46, glossy compare 248, scaling 269-286; sixteenth session, four calls: scaling 229-266, generated levels' profile 129, profile 215, compare 244, collision 80, `runtime --frames 20` 9; seventeenth session, with four more profile rows: profile 238, scaling 254, compare 259, collision 74, rooms 169, the generated levels' profile over 150 (cut short: give it 250); eighteenth session, two calls: the 2-32-shape sweep 59 at 4K and 52 at 1080p, A/B steps of 33-40 s, the full profile 262 s with the layer rows (330 s now with the subgroup-box rows), and a third call with compare and scaling lost when the machine stopped answering); split it into calls of at most 600 s each (profile, scaling, collision; compare; rooms and bounces), and pack the archive after each step so that a call cut short still brings back what it measured.
# Twenty-third session (an H100, one call): compare 246 s, collision 72, scalecounts 102.
# Twenty-ninth session (H200, four calls): profile 424 s (cut at the old 330 s limit the
# first time), collision 71, compare 255, scalecounts 95, generated over 200 (cut).
# Thirtieth session (H100): scaling 251 s (its full threshold and coverage sweeps).
# Thirty-first session (H100, three calls): profile 188-201 s, collision 78, compare 230,
# scalecounts 99.
# Thirty-second session (H100, one call for these suites): profile 206 s, compare 241.
# Before it, h200_candidates.sh times the bench options not yet timed (run it first and
# set the defaults from it). `runtime` now also reports each frame's CPU time of prepare +
# encode (`cpu_ms`, the host CPU's: docs/perf/cpu.md).
# `bash h200.sh STEP...` runs only the named steps (profile, profilefull, collision,
# scaling, compare, scalecounts, generated, rooms, bounces), in this order; no argument runs them all (split them into
# calls of at most 600 s). The profile leaves out the rows h200_candidates.sh timed (SKIP
# below).
STEPS=" $* "
want() { [ "$STEPS" = "  " ] || [[ "$STEPS" == *" $1 "* ]]; }
source crates/ppr-bench/scripts/h200_env.sh
# The GPU's clocks, power and temperature every half second, beside the results: the
# scaling suite's 10 000-shape rows have met a slow state (every pass 1.5-2x slower) after
# its heavy rows; this log says whether the clocks fell with it.
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,temperature.gpu,clocks_throttle_reasons.active --format=csv -lms 500 > "$R/clocks_$(date +%s).csv" 2>&1 &
SKIP=()
for row in "culling on, subgroup box" "subgroup box" "culling on, empty, subgroup box" \
    "culling on, subgroup box atomics" "culling on, empty, subgroup box atomics" \
    "subgroup culling on" "subgroup culling only" "subgroup culling only, no inside entries" \
    "subgroup culling only, tests only"; do
  SKIP+=(--skip-profile-row "$row")
done
# Rows of questions settled in earlier sessions (each variant slower or the same, its
# default kept; runtime.md says where): left out of `profile`, which keeps the rows the
# numbers of record and the gap's breakdown read (28 of 67 rows: ~180 s instead of
# 424); `profilefull` runs them all (only when named).
SETTLED=()
for row in "culling on, empty, lists box only" "culling on, separate lists" \
    "culling on, empty, separate lists" "separate lists" "culling on, no inside entries" \
    "culling on, prefetch" "culling on, empty, prefetch" "occluder lists" "storage tests" \
    "spread quads" "occupancy pad 16 KiB" "occupancy pad 32 KiB" \
    "occupancy pad 38 KiB" "clear pass every frame" "layers: no water stretch" \
    "layers: full stretch walk" "layers: after reflection" "classify own pass" \
    "frame span, layers own pass" "frame span, layers after reflection" \
    "frame span, classify own pass" "frame span, classify own pass, layers own pass" \
    "frame span, separate upload copies" "frame span, layered reflection own pass" \
    "layered reflection own pass" "reflection: mirrors, quads" "reflection: mirrors, quads, empty" \
    "reflection: mirrors, clear pass every frame" "reflection: mirrors, indirect off" \
    "reflection: mirrors, indirect on" "reflection: indirect dispatch" \
    "reflection: mirrors, indirect dispatch" "reflection: tile loop 1024" \
    "reflection: mirrors, tile loop 1024" "reflection: tile loop 2048" \
    "reflection: mirrors, tile loop 2048" "reflection: tile loop 8192" \
    "reflection: mirrors, tile loop 8192"; do
  SETTLED+=(--skip-profile-row "$row")
done
want profile && step profile 400 $B runtime $C --projection-profile "${SKIP[@]}" "${SETTLED[@]}" --write-probe --frames 20 --out $R/profile
[[ "$STEPS" == *" profilefull "* ]] && step profilefull 540 $B runtime $C --projection-profile "${SKIP[@]}" --write-probe --frames 20 --out $R/profilefull
want collision && step collision 110 $B compare $C --out $R/collision --scene collision-world --reference mirror --resolution 1080p --resolution 4k --frames 10 --technique ppr --technique ppr:subgroups=off --technique ppr-raw --technique ppr:tier=half --technique ssr-low --technique exact
want scaling && step scaling 300 $B scaling $C --out $R/scaling --counts 1,10,100,1000,10000 --threshold-counts 1,2,4,8,16,32,64,128,256,512 --coverages 0.1,0.2,0.3,0.4,0.5,0.6
T="--technique ppr-raw --technique ppr-holes --technique ppr-filter --technique ppr --technique ppr:glossy=off --technique ppr:fade=0.1 --technique ppr:tier=half --technique ppr:tier=quarter --technique exact --technique ssr-brute --technique ssr-low --technique ssr-low:stride=16,refine=4 --technique ssr-hiz --technique ssr-glossy --technique sspr"
want compare && step compare 290 $B compare $C --out $R/compare --reference mirror --scene demo --scene kitchen --resolution 1080p --resolution 4k --frames 20 $T
# The scaling goal's rows alone (shape counts; the threshold and coverage sweeps cut to one
# point each), when the device time left does not fit the full sweep.
want scalecounts && step scalecounts 240 $B scaling $C --out $R/scalecounts --frames 10 --counts 1,10,100,1000,10000 --threshold-counts 8 --coverages 0.3
# The generated levels' profile (runtime.md, "Generated levels").
want generated && step generated 300 $B runtime $C --projection-profile "${SKIP[@]}" "${SETTLED[@]}" --frames 10 --scene stairway-1000 --scene stairway-10000 --scene rooms-1000 --resolution 4k --out $R/stprof
want rooms && step rooms 330 $B compare $C --out $R/rooms --scene mirror-room --scene mirror-room-6 --scene mirror-corridor --resolution 4k --frames 20 --technique ppr-raw --technique ppr --technique ppr:tier=half --technique ppr:tier=quarter --technique exact --technique ssr-brute --technique ssr-low --technique sspr
# Mirror facing mirror (docs/perf/comparison.md; 1080p in the 2026-12-02 run):
want bounces && step bounces 200 $B compare $C --out $R/bounces --scene mirror-room --scene mirror-room-6 --scene mirror-corridor --resolution 1080p --frames 20 --technique ppr --technique ppr:reference-bounces=2 --technique ppr:bounces=2 --technique ppr:tier=half,bounces=2 --technique ssr-brute:reference-bounces=2 --technique exact --technique exact:bounces=2
