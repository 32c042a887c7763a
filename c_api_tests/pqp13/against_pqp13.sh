#!/usr/bin/env bash
# Builds every PQP 1.3 program of c_api_tests/pqp13/ (in each C++ standard programs.txt lists), and
# c_api_tests/legacy_boxes.cpp and examples/demo_legacy.cpp, twice: against UNC's PQP 1.3 (its
# installed headers and libPQP.a) and against pqp-rs (include/ and libpqp from cargo). Runs both,
# and diffs their standard outputs. See c_api_tests/README.md, "Checked against PQP 1.3".
#
#   c_api_tests/pqp13/against_pqp13.sh PQP13_DIR [PQP_RS_LIB_DIR]
#   PQP13_FLOAT_DIR=DIR c_api_tests/pqp13/against_pqp13.sh ...   (also the float program)
#
# PQP13_DIR holds PQP 1.3 as its Makefile installs it: include/PQP.h ... and lib/libPQP.a, and its
# src/ (PQP 1.3 installs no MatVec.h or TriDist.h; its programs take them from src/).
# PQP13_FLOAT_DIR, if set, is a second PQP 1.3 built with PQP_REAL float (its PQP_Compile.h edited,
# as PQP 1.3 instructs), for the programs built with -DPQP_USE_FLOAT; without it they are skipped.
# PQP_RS_LIB_DIR holds libpqp.so (default: target/release; run `cargo build --release` first).
# Output: one line per build, "program std: pqp13=<status> pqp-rs=<status> output=<same|DIFFERS>";
# the outputs and diffs are kept in $OUT (default /tmp/pqp13-compare).
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
pqp13=${1:?usage: against_pqp13.sh PQP13_DIR [PQP_RS_LIB_DIR]}
pqp13=$(cd "$pqp13" && pwd)
rslib=${2:-$root/target/release}
out=${OUT:-/tmp/pqp13-compare}
mkdir -p "$out/lib"
# Programs look for the soname libpqp.so.1; cargo names its file libpqp.so.
ln -sf "$(cd "$rslib" && pwd)/libpqp.so" "$out/lib/libpqp.so.1"
ln -sf "$(cd "$rslib" && pwd)/libpqp.so" "$out/lib/libpqp.so"
rslib=$out/lib
cxx=${CXX:-g++}
harness="-I$root/c_tests/harness"

# run NAME STD SOURCE [FLAGS...]: one program in one standard, against both.
run() {
    local name=$1 std=$2 src=$3
    shift 3
    local tag="${name}_cxx${std}" a b same peer=$pqp13
    case " $* " in
        *" -DPQP_USE_FLOAT "*)
            if [ -z "${PQP13_FLOAT_DIR:-}" ]; then
                echo "$name c++$std: skipped (PQP_REAL float: set PQP13_FLOAT_DIR)"
                return
            fi
            peer=$(cd "$PQP13_FLOAT_DIR" && pwd) ;;
    esac
    if "$cxx" -std=c++"$std" -O2 -w "$@" $harness -I"$peer/include" -I"$peer/src" "$src" \
        -L"$peer/lib" -lPQP -lm -o "$out/$tag.pqp13" 2> "$out/$tag.pqp13.build"; then
        timeout 60 "$out/$tag.pqp13" $ARGS > "$out/$tag.pqp13.out" 2> "$out/$tag.pqp13.err"
        a="exit $?"
    else
        a="does-not-compile"
        : > "$out/$tag.pqp13.out"
    fi
    if "$cxx" -std=c++"$std" -O2 -Wall -Wextra -pedantic -Werror "$@" $harness -I"$root/include" \
        "$src" -L"$rslib" -lpqp -Wl,-rpath,"$rslib" -o "$out/$tag.pqprs" \
        2> "$out/$tag.pqprs.build"; then
        timeout 60 "$out/$tag.pqprs" $ARGS > "$out/$tag.pqprs.out" 2> "$out/$tag.pqprs.err"
        b="exit $?"
    else
        b="does-not-compile"
        : > "$out/$tag.pqprs.out"
    fi
    if [ -n "$FILTER" ]; then
        for side in pqp13 pqprs; do
            awk "$FILTER" "$out/$tag.$side.out" > "$out/$tag.$side.kept"
        done
    else
        cp "$out/$tag.pqp13.out" "$out/$tag.pqp13.kept"
        cp "$out/$tag.pqprs.out" "$out/$tag.pqprs.kept"
    fi
    if diff "$out/$tag.pqp13.kept" "$out/$tag.pqprs.kept" > "$out/$tag.diff"; then
        same=same
    else
        same="DIFFERS ($(grep -c '^[<>]' "$out/$tag.diff") lines, $out/$tag.diff)"
    fi
    echo "$name c++$std: pqp13=$a pqp-rs=$b output=$same"
}

ARGS="" FILTER=""
while read -r name rest; do
    case "$name" in '#'* | '') continue ;; esac
    stds=() flags=()
    for w in $rest; do
        case "$w" in -*) flags+=("$w") ;; *) stds+=("$w") ;; esac
    done
    for std in "${stds[@]}"; do
        run "$name" "$std" "$root/c_api_tests/pqp13/$name.cpp" "${flags[@]}"
    done
done < "$root/c_api_tests/pqp13/programs.txt"

run legacy_boxes 98 "$root/c_api_tests/legacy_boxes.cpp"
# The demo prints times and memory sizes, which differ legitimately, and an approximate distance
# (within 5%), which may: compare the triangle counts and, per step, x, the pair count, the exact
# distance and the tolerance answer.
ARGS="$root/examples/models/bunny.tris $root/examples/models/torus.tris"
FILTER='/triangles/ {print $1, $2} $2 == "|" {print $1, $3, $6, $12}'
run demo_legacy 11 "$root/examples/demo_legacy.cpp"
