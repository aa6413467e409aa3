#!/usr/bin/env bash
# The skinning scaling curve (issue 18, item 3) on a machine of many cores, as one
# short run: the host's facts (cores, NUMA nodes, memory), then `chasles skin --bench` at
# 10^6, 4*10^6 and 10^7 vertices (SIZES) on 1, 2, 4, ... up to every thread, each kernel
# beside the copy of the bytes it moves; on a machine of several NUMA nodes, the same on
# one node's cores and memory and with memory interleaved over the nodes (numactl), to
# tell NUMA from the rest.
#
# Usage: scripts/scaling.sh [CHASLES_BINARY] [OUT_DIR]
#   CHASLES_BINARY  default target/release/chasles (build: cargo build --release -p chasles-cli;
#                   strip a copy to carry it to another machine: about 14 MB; it needs
#                   glibc 2.35 or newer, as built on this Debian 12)
#   OUT_DIR         where scaling.md and host.txt go (default: the current folder)
# Environment:
#   SIZES           the mesh sizes (default 1000000,4000000,10000000: a many-core host's
#                   last-level cache may hold the 288 MB of 4*10^6, not the 720 MB of 10^7)
set -euo pipefail
bin=${1:-target/release/chasles}
out=${2:-.}
sizes=${SIZES:-1000000,4000000,10000000}
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
    lscpu -e || true
    free -g || true
    if command -v numactl >/dev/null; then
        numactl --hardware || true
    else
        echo "numactl: not installed"
    fi
} >"$out/host.txt" 2>&1
# NUMA nodes with CPUs (a kernel without NUMA shows none: one node).
shopt -s nullglob
nodes=0
for d in /sys/devices/system/node/node[0-9]*; do
    [ -s "$d/cpulist" ] && nodes=$((nodes + 1))
done
[ "$nodes" -ge 1 ] || nodes=1
# How many CPUs node 0 has (its cpulist, e.g. 0-7,16-23).
node0_cpus() {
    local n=0 r a b
    IFS=, read -ra ranges </sys/devices/system/node/node0/cpulist
    for r in "${ranges[@]}"; do
        a=${r%-*}
        b=${r#*-}
        n=$((n + b - a + 1))
    done
    echo "$n"
}
bench() {
    "$@" "$bin" skin --bench --bench-vertices "$sizes" --bench-threads "$threads" \
        --bench-rounds 7
}
{
    echo "# chasles skin --bench, threads $threads, $n CPUs, $nodes NUMA node(s)"
    bench env
    if [ "$nodes" -gt 1 ] && command -v numactl >/dev/null; then
        echo
        echo "# node 0's cores and memory only (numactl --cpunodebind=0 --membind=0)"
        threads=$(curve "$(node0_cpus)")
        bench numactl --cpunodebind=0 --membind=0
        echo
        echo "# memory interleaved over every node (numactl --interleave=all)"
        threads=$(curve "$n")
        bench numactl --interleave=all
    fi
} 2>&1 | tee "$out/scaling.md"
