#!/bin/sh
# Builds the release library and the benchmark, prints the machine, runs everything.
#   bench/run.sh [pqp_bench options...]     e.g. bench/run.sh --only spheres,coherent
# Output is Markdown, ready for BENCHMARKS.md.
set -eu
cd "$(dirname "$0")/.."
echo "## Machine"
echo
lscpu | grep -E '^(Model name|CPU\(s\)|Thread\(s\) per core|Core\(s\) per socket|Socket\(s\)|L2 cache|L3 cache)' | sed 's/^/    /'
echo "    load average before the run: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "    $(rustc --version); $(c++ --version | head -1)"
echo
cargo build --release --quiet
cmake -S bench -B build-bench -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-bench >/dev/null
./build-bench/pqp_bench "$@"
echo
echo "## BVTT efficiency (workload 1)"
echo
cargo run --release --quiet --example bvtt_efficiency
echo
echo "    load average after the run: $(cut -d' ' -f1-3 /proc/loadavg)"
