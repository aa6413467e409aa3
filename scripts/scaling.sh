#!/usr/bin/env bash
# The skinning scaling curve (issue 18, item 3) on a machine of many cores, as one short
# run: the host's facts (cores, NUMA nodes, memory), then `chasles skin --bench` at 10^6
# and 4*10^6 vertices on 1, 2, 4, ... up to every thread, each kernel beside the copy of
# the bytes it moves; on a machine of several NUMA nodes, the same on one node's cores and
# memory and with memory interleaved over the nodes (numactl), to tell NUMA from the rest.
#
# Usage: scripts/scaling.sh [CHASLES_BINARY] [OUT_DIR]
#   CHASLES_BINARY  default target/release/chasles (build: cargo build --release -p chasles-cli;
#                   strip a copy to carry it to another machine: about 14 MB)
#   OUT_DIR         where scaling.md and host.txt go (default: the current folder)
set -euo pipefail
bin=${1:-target/release/chasles}
out=${2:-.}
mkdir -p "$out"
n=$(nproc)
# 1, 2, 4, ... below $1, then $1.
curve() {
    local list=1 t=2
    while [ "$t" -lt "$1" ]; do
        list+=",$t"
        t=$((t * 2))
    done
    [ "$1" -gt 1 ] && list+=",$1"
    echo "$list"
}
threads=$(curve "$n")
{
    echo "# host"
    date -u
    uname -a
    lscpu || true
    free -g || true
    command -v numactl >/dev/null && numactl --hardware || echo "numactl: not installed"
} >"$out/host.txt" 2>&1
nodes=$(ls -d /sys/devices/system/node/node[0-9]* 2>/dev/null | wc -l)
bench() {
    "$@" "$bin" skin --bench --bench-vertices 1000000,4000000 --bench-threads "$threads" \
        --bench-rounds 7
}
{
    echo "# chasles skin --bench, threads $threads, $n CPUs, $nodes NUMA node(s)"
    bench env
    if [ "$nodes" -gt 1 ] && command -v numactl >/dev/null; then
        echo
        echo "# node 0's cores and memory only (numactl --cpunodebind=0 --membind=0)"
        threads=$(curve "$(lscpu -p=NODE | grep -c '^0$')")
        bench numactl --cpunodebind=0 --membind=0
        echo
        echo "# memory interleaved over every node (numactl --interleave=all)"
        threads=$(curve "$n")
        bench numactl --interleave=all
    fi
} 2>&1 | tee "$out/scaling.md"
