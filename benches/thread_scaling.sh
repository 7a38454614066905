#!/usr/bin/env bash
# Thread scaling of whole `ehl` runs (BENCHMARKS.md, "Thread scaling on 16 cores"): each case
# with RAYON_NUM_THREADS = 1 2 4 8 16, then a 48-point sweep with --jobs = 1 .. 16.
# Usage, from the repository root: [THREADS="1 2"] [SUITE=thermal] benches/thread_scaling.sh [path/to/ehl]
# (default target/release/ehl; THREADS the thread counts, default 1 2 4 8 16; SUITE=thermal runs
# the thermal cases of BENCHMARKS.md "Thermal EHL" instead); one line per run on stdout (the
# solve time is summary.json's wall_time_s).
set -u
B=${1:-target/release/ehl}
OUTDIR=$(mktemp -d)
trap 'rm -rf "$OUTDIR"' EXIT
nproc
grep -m1 "model name" /proc/cpuinfo
THREADS=${THREADS:-"1 2 4 8 16"}
one() { # name threads args...
    local name=$1 t=$2
    shift 2
    local o=$OUTDIR/${name}_$t
    local s e w rc
    s=$(date +%s%N)
    RAYON_NUM_THREADS=$t "$B" run "$@" -q --out "$o" >/dev/null 2>"$o.err"
    rc=$?
    e=$(date +%s%N)
    w=$(grep -o '"wall_time_s": *[0-9.e+-]*' "$o/summary.json" 2>/dev/null | head -1 | sed 's/.*: *//')
    echo "$name threads $t rc $rc whole $(((e - s) / 1000000)) ms solve ${w:-?} s"
}
each() {
    local name=$1
    shift
    for t in $THREADS; do one "$name" "$t" "$@"; done
}
THERMAL='thermal={inlet_temperature=313.0, viscosity_temperature=1.1, thermal_expansion=6.5e-4, conductivity=0.14, heat_capacity=2000.0, points_across_film=7}'
if [ "${SUITE:-}" = thermal ]; then
    R=examples/ehl_thesis_ch2_roller.toml
    P=examples/ehl_thesis_ch3_single_pit.toml
    sed '/^\[thermal\]/,$d' examples/ehl_thermal_ball.toml >"$OUTDIR/ball_isothermal.toml"
    each roller256x512 $R --set grid.nx=256 --set grid.ny=512
    each thermal_roller256x512 $R --set grid.nx=256 --set grid.ny=512 --set "$THERMAL"
    each thermal_roller256x128_srr0.3 $R --set grid.nx=256 --set grid.ny=128 --set "$THERMAL" \
        --set motion.slide_to_roll=0.3
    each ball129 "$OUTDIR/ball_isothermal.toml"
    each thermal_ball129 examples/ehl_thermal_ball.toml
    each thermal_pit128_20steps $P --set grid.nx=128 --set grid.ny=128 --set "$THERMAL" \
        --set motion.travel.steps=20 --set motion.travel.to=-0.733e-3 --set 'output.snapshots=[]'
    for t in ${PASSAGE_THREADS:-16}; do
        one thermal_pit256_passage "$t" $P --set "$THERMAL" --set 'output.snapshots=[]'
    done
    each thermal_line examples/ehl_thermal_line.toml
    for j in $THREADS; do
        s=$(date +%s%N)
        RAYON_NUM_THREADS=1 "$B" sweep examples/ehl_thermal_line.toml --vary motion.slide_to_roll=0:0.3:48 \
            --set 'output.snapshots=[]' --jobs "$j" -q --out "$OUTDIR/tsweep_$j" >/dev/null 2>&1
        rc=$?
        e=$(date +%s%N)
        echo "thermal_line_sweep48 jobs $j rc $rc whole $(((e - s) / 1000000)) ms"
    done
    exit 0
fi
each dry256x2048 examples/dry_roller_mirror1_psi.toml --set grid.nx=256 --set grid.ny=2048
each roller512x128 examples/ehl_thesis_ch2_roller.toml
each roller512x512 examples/ehl_thesis_ch2_roller.toml --set grid.ny=512
each roller1024x512 examples/ehl_thesis_ch2_roller.toml --set grid.nx=1024 --set grid.ny=512
each thermal_roller256x128 examples/ehl_thesis_ch2_roller.toml --set grid.nx=256 --set grid.ny=128 \
    --set 'thermal={inlet_temperature=313.0, viscosity_temperature=1.1, thermal_expansion=6.5e-4, conductivity=0.14, heat_capacity=2000.0}' \
    --set motion.slide_to_roll=0.3
for n in 128 256; do
    each pit${n}_30steps examples/ehl_thesis_ch3_single_pit.toml --set grid.nx=$n --set grid.ny=$n \
        --set motion.travel.steps=30 --set motion.travel.to=-0.6e-3 --set 'output.snapshots=[]'
done
each waviness2048 examples/ehl_transient_line_waviness.toml
each thermal_line examples/ehl_thermal_line.toml
for j in $THREADS; do
    s=$(date +%s%N)
    RAYON_NUM_THREADS=1 "$B" sweep examples/ehl_thesis_ch2_roller.toml --set grid.nx=256 --set grid.ny=128 \
        --vary motion.slide_to_roll=0:0.3:48 --jobs "$j" -q --out "$OUTDIR/sweep_$j" >/dev/null 2>&1
    rc=$?
    e=$(date +%s%N)
    echo "sweep48 jobs $j rc $rc whole $(((e - s) / 1000000)) ms"
done
