#!/usr/bin/env bash
# The ODE adapter's cost over the core, in instructions per call (callgrind), for every case of
# tests/ode/adapter_overhead.cpp: each case runs once through gdc::ode::collide and once through
# gdc::collide with the same polytopes, poses and A/B order; overhead = the difference. The adapter
# runs with its pair cache off; two more columns: with the cache on when nothing moves (every call
# answered from it) and when every geom moved a little since the last call (every call a query).
# Usage: tests/ode/adapter_overhead.sh [path/to/ode_adapter_overhead]   (default: build/tests/ode/...)
set -euo pipefail
binary=${1:-build/tests/ode/ode_adapter_overhead}
printf "%-20s %10s %10s %9s %10s %14s  %s\n" case adapter core overhead cached cached-moving "contacts/call"
for name in box_box box_plane hull_plane hull_hull box_box_separated hull_scene_2000; do
    rounds=50
    [ "$name" = hull_scene_2000 ] && rounds=2  # 1000 pairs a round
    declare -A perCall
    for mode in adapter core cached cached-moving; do
        output=$(valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file=/dev/null \
            "$binary" "$name" "$mode" "$rounds" 2>&1)
        calls=$(grep -o "calls [0-9]*" <<<"$output" | awk '{print $2}')
        collected=$(grep -o "Collected : [0-9]*" <<<"$output" | awk '{print $3}')
        perCall[$mode]=$(awk -v i="$collected" -v c="$calls" 'BEGIN {printf "%.1f", i / c}')
        contacts=$(grep -o "contacts/call [0-9.]*" <<<"$output" | awk '{print $2}')
    done
    printf "%-20s %10s %10s %9.1f %10s %14s  %s\n" "$name" "${perCall[adapter]}" "${perCall[core]}" \
        "$(awk -v a="${perCall[adapter]}" -v c="${perCall[core]}" 'BEGIN {print a - c}')" \
        "${perCall[cached]}" "${perCall[cached-moving]}" "$contacts"
done
