#!/usr/bin/env bash
# The campaign controller at scale (issue 37; figures in docs/benchmarks.md).
#
# For each point count (default 1000 10000 100000): `bumpsim campaign init`
# of a one-factor Latin hypercube whose solver is `true` (a no-op), twice;
# the baseline on the second copy: the task script (`sh run-point.sh
# POINT_FOLDER`) over its point folders with `xargs -P2`, no controller;
# then `bumpsim campaign run` of the first with the local executor and 2
# slots. Nothing is deleted until the end: on ext4 without a journal, files
# made within seconds of many deletions cost more (the allocator steps over
# recently freed inodes), which would burden whichever step came after a
# deletion. Prints, per count: the
# init time and its peak memory, the run's time per point and its peak
# memory (the controller's resident set, the tasks not included), the
# baseline's time per point, and the controller's overhead per point (run −
# baseline), in wall time and in CPU time (user + system, the tasks'
# included on both sides, so the difference is the controller's own; it
# moves less with the machine's load than wall time). Times from
# /usr/bin/time (10 ms resolution). The controller's own cost, robust to
# the load: `perf stat -i` (counters not inherited by the tasks it starts)
# counts the controller process alone, its CPU time (task-clock, ns) and
# its system calls (raw_syscalls:sys_enter), per point; without perf those
# columns are "-".
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

timed() { # output file, command...: elapsed s, peak KB and CPU s into the file
    local out="$1"
    shift
    /usr/bin/time -f '%e %M %U %S' -o "$out" "$@" >/dev/null
}

per_point() { # seconds, points: ms per point
    awk -v s="$1" -v n="$2" 'BEGIN { printf "%.2f", 1000 * s / n }'
}

echo "bumpsim campaign, local executor, 2 slots, solver 'true' ($(nproc) CPUs; load $(cut -d' ' -f1-3 /proc/loadavg))"
echo "| points | init | init CPU | init peak | run per point | run peak | xargs -P2 per point | controller overhead per point | controller CPU per point | controller's own CPU per point (perf) | its system calls per point |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
perf=() # the controller alone, counters not inherited by its tasks
if command -v perf >/dev/null && perf stat -i -e task-clock true >/dev/null 2>&1; then
    perf=(perf stat -i -x, -e task-clock,raw_syscalls:sys_enter -o "$work/run.perf")
fi
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
    base="$work/base$n"
    timed "$work/init.time" "$bin" campaign init "$work/c.toml" -o "$c"
    "$bin" campaign init "$work/c.toml" -o "$base" >/dev/null
    # the baseline: the same tasks, two at a time, without a controller
    timed "$work/xargs.time" sh -c "find '$base/points' -mindepth 1 -maxdepth 1 -type d | sort | xargs -P2 -n1 sh '$base/run-point.sh'"
    : > "$work/run.perf"
    timed "$work/run.time" "${perf[@]}" "$bin" campaign run "$c"
    "$bin" campaign status "$c" | grep -q "$n points: $n done" || { echo "run of $n points incomplete" >&2; exit 1; }
    read -r init_s init_kb init_u init_k < "$work/init.time"
    read -r run_s run_kb run_u run_k < "$work/run.time"
    read -r base_s _ base_u base_k < "$work/xargs.time"
    init_cpu="$(awk -v u="$init_u" -v k="$init_k" 'BEGIN { printf "%.2f", u + k }')"
    cpu_ms="$(awk -v a="$run_u" -v b="$run_k" -v c="$base_u" -v d="$base_k" -v n="$n" \
        'BEGIN { printf "%.2f", 1000 * ((a + b) - (c + d)) / n }')"
    run_ms="$(per_point "$run_s" "$n")"
    base_ms="$(per_point "$base_s" "$n")"
    overhead="$(awk -v a="$run_ms" -v b="$base_ms" 'BEGIN { printf "%.2f", a - b }')"
    own_ms="$(awk -F, -v n="$n" '$3 == "task-clock" { printf "%.3f ms", $1 / n }' "$work/run.perf")"
    calls="$(awk -F, -v n="$n" '$3 == "raw_syscalls:sys_enter" { printf "%.1f", $1 / n }' "$work/run.perf")"
    echo "| $n | ${init_s} s | ${init_cpu} s | $((init_kb / 1024)) MB | ${run_ms} ms | $((run_kb / 1024)) MB | ${base_ms} ms | ${overhead} ms | ${cpu_ms} ms | ${own_ms:--} | ${calls:--} |"
done
echo "(load afterwards $(cut -d' ' -f1-3 /proc/loadavg))"
