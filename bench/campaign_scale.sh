#!/usr/bin/env bash
# The campaign controller at scale (issue 37; figures in docs/benchmarks.md).
#
# For each point count (default 1000 10000 100000): `bumpsim campaign init`
# of a one-factor Latin hypercube whose solver is `true` (a no-op), then
# `bumpsim campaign run` with the local executor and 2 slots, then the
# baseline: the same task script (`sh run-point.sh POINT_FOLDER`) over the
# same point folders with `xargs -P2`, no controller. Prints, per count: the
# init time and its peak memory, the run's time per point and its peak
# memory (the controller's resident set, the tasks not included), the
# baseline's time per point, and the controller's overhead per point (run −
# baseline). Wall times from /usr/bin/time (10 ms resolution).
#
# Usage: bench/campaign_scale.sh [COUNT ...]   (BUMPSIM=path/to/bumpsim; default
# target/release/bumpsim: build it first with `cargo build --release -p bumpsim-cli`)
set -euo pipefail
cd "$(dirname "$0")/.."

bin="$(realpath "${BUMPSIM:-target/release/bumpsim}")"
[ -x "$bin" ] || { echo "no $bin: cargo build --release -p bumpsim-cli" >&2; exit 2; }
counts=("$@")
[ "${#counts[@]}" -gt 0 ] || counts=(1000 10000 100000)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
printf 'k = {{k}}\n' > "$work/deck.tmpl"

timed() { # output file, command...: elapsed s and peak KB into the file
    local out="$1"
    shift
    /usr/bin/time -f '%e %M' -o "$out" "$@" >/dev/null
}

per_point() { # seconds, points: ms per point
    awk -v s="$1" -v n="$2" 'BEGIN { printf "%.2f", 1000 * s / n }'
}

echo "bumpsim campaign, local executor, 2 slots, solver 'true' ($(nproc) CPUs; load $(cut -d' ' -f1-3 /proc/loadavg))"
echo "| points | init | init peak | run per point | run peak | xargs -P2 per point | controller overhead per point |"
echo "|---:|---:|---:|---:|---:|---:|---:|"
for n in "${counts[@]}"; do
    cat > "$work/c.toml" <<EOF
name = "scale"
[design]
kind = "lhs"
runs = $n
factors = [{ name = "k", low = 1, high = 2 }]
[template]
file = "deck.tmpl"
[solver]
command = ["true"]
[executor]
slots = 2
EOF
    c="$work/c$n"
    timed "$work/init.time" "$bin" campaign init "$work/c.toml" -o "$c"
    timed "$work/run.time" "$bin" campaign run "$c"
    "$bin" campaign status "$c" | grep -q "$n points: $n done" || { echo "run of $n points incomplete" >&2; exit 1; }
    # the baseline: the same tasks, markers cleared, two at a time without a controller
    find "$c/points" -name .bumpsim-exit -delete
    timed "$work/xargs.time" sh -c "find '$c/points' -mindepth 1 -maxdepth 1 -type d | sort | xargs -P2 -n1 sh '$c/run-point.sh'"
    read -r init_s init_kb < "$work/init.time"
    read -r run_s run_kb < "$work/run.time"
    read -r base_s _ < "$work/xargs.time"
    run_ms="$(per_point "$run_s" "$n")"
    base_ms="$(per_point "$base_s" "$n")"
    overhead="$(awk -v a="$run_ms" -v b="$base_ms" 'BEGIN { printf "%.2f", a - b }')"
    echo "| $n | ${init_s} s | $((init_kb / 1024)) MB | ${run_ms} ms | $((run_kb / 1024)) MB | ${base_ms} ms | ${overhead} ms |"
    rm -rf "$c"
done
echo "(load afterwards $(cut -d' ' -f1-3 /proc/loadavg))"
