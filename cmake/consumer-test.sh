#!/usr/bin/env bash
# Install/consumer test (run by ctest as install_consumer): installs a build into a temporary
# prefix, then, in a temporary directory outside the source tree, checks what a user gets:
#   - the installed files and links, the shared library's soname (readelf -d), and that it
#     exports exactly the functions pqp/pqp.h declares;
#   - every installed header compiles alone (C99 for pqp/pqp.h, C++11..20 for all five),
#     with -Wall -Wextra -pedantic -Werror;
#   - the PQP 1.3 programs of c_api_tests/pqp13 (programs.txt), each in every standard listed,
#     with pkg-config, and with find_package(pqp) in its first;
#   - the installed libraries carry no debug information (when installed stripped);
#   - programs built with `pkg-config --cflags --libs pqp` (which run without LD_LIBRARY_PATH:
#     the .pc file gives an rpath for a prefix outside the loader's path), with
#     `-static $(pkg-config --static --libs pqp)` (no dynamic section at all), with libpqp.a and
#     pkg-config --static's private libraries, with find_package(pqp) + PQP::PQP (and PQP::PQP_static), and PQP 1.3 style with
#     -I<prefix>/include -L<prefix>/lib -lPQP, all of which must run and answer correctly.
#
# Usage: consumer-test.sh BUILD_DIR CONSUMER_SOURCE_DIR CC CXX CMAKE [LIBDIR [INCLUDEDIR [STRIP]]]
# (LIBDIR and INCLUDEDIR relative to the prefix, as CMAKE_INSTALL_LIBDIR/INCLUDEDIR; default
# lib and include; STRIP is ON when the install strips the libraries, the default).
set -euo pipefail

build_dir=$1
consumer_src=$2
cc=$3
cxx=$4
cmake=$5
libdir=${6:-lib}
includedir=${7:-include}
strip=${8:-ON}

# The repository (for the PQP 1.3 programs of c_api_tests/pqp13 and the brute-force referee).
repo=$(cd "$consumer_src/../.." && pwd)
pqp13=$repo/c_api_tests/pqp13
harness=$repo/c_tests/harness

work=$(mktemp -d "${TMPDIR:-/tmp}/pqp-consumer.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
warn=(-Wall -Wextra -pedantic -Werror)

step() { printf '\n== %s\n' "$*"; }
fail() {
    echo "FAIL: $*" >&2
    exit 1
}

step "install into $prefix"
"$cmake" --install "$build_dir" --prefix "$prefix"

cp -r "$consumer_src" "$work/src"
cd "$work"
lib=$prefix/$libdir
inc=$prefix/$includedir

step "installed files"
for f in "$lib"/{libpqp.so.1.0.0,libpqp.so.1,libpqp.so,libpqp.a,libPQP.so,libPQP.a} \
    "$inc"/{pqp/pqp.h,pqp/pqp_cxx.h,PQP.h,PQP_Compile.h,PQP_Internal.h,Tri.h,BV.h,MatVec.h,TriDist.h} "$lib"/pkgconfig/pqp.pc \
    "$lib"/cmake/pqp/{pqpConfig.cmake,pqpConfigVersion.cmake}; do
    [[ -e $f ]] || fail "missing $f"
done
for l in libpqp.so.1 libpqp.so libPQP.so libPQP.a; do
    [[ -L $lib/$l ]] || fail "$l is not a symbolic link"
done
[[ $(readlink -f "$lib/libpqp.so") == $(readlink -f "$lib/libpqp.so.1.0.0") ]] || fail "libpqp.so does not lead to libpqp.so.1.0.0"
[[ $(readlink -f "$lib/libPQP.so") == $(readlink -f "$lib/libpqp.so.1.0.0") ]] || fail "libPQP.so does not lead to libpqp.so.1.0.0"
[[ $(readlink -f "$lib/libPQP.a") == $(readlink -f "$lib/libpqp.a") ]] || fail "libPQP.a does not lead to libpqp.a"
ls -l "$lib"

step "debug information"
if [[ $strip == ON ]]; then
    for f in libpqp.so.1.0.0 libpqp.a; do
        if readelf -S "$lib/$f" | grep -q '\.debug_info'; then fail "$f carries debug information"; fi
    done
    echo "stripped: ok"
else
    echo "installed unstripped (PQP_INSTALL_STRIP=OFF)"
fi

step "soname"
readelf -d "$lib/libpqp.so.1.0.0" | grep SONAME
readelf -d "$lib/libpqp.so.1.0.0" | grep -q 'Library soname: \[libpqp\.so\.1\]' || fail "soname is not libpqp.so.1"

step "exported symbols are exactly the functions pqp.h declares"
exported=$(nm -D --defined-only "$lib/libpqp.so.1.0.0" | awk '{print $3}' | sort)
declared=$(grep -oE '\bpqp_[a-z0-9_]+\(' "$inc/pqp/pqp.h" | tr -d '(' | sort -u)
if [[ $exported != "$declared" ]]; then
    diff <(echo "$declared") <(echo "$exported") || true
    fail "exported symbols differ from the header's functions"
fi
echo "$(echo "$exported" | wc -l) functions"

step "every header compiles alone"
printf '#include <pqp/pqp.h>\n' >h_c.c
"$cc" -std=c99 "${warn[@]}" -I"$inc" -c h_c.c -o h_c.o
"$cc" -std=c11 "${warn[@]}" -I"$inc" -c h_c.c -o h_c.o
for std in c++98 c++11 c++14 c++17 c++20; do
    for h in pqp/pqp.h pqp/pqp_cxx.h PQP.h PQP_Compile.h PQP_Internal.h Tri.h BV.h MatVec.h TriDist.h; do
        printf '#include <%s>\n' "$h" >h_cxx.cpp
        "$cxx" -std=$std "${warn[@]}" -I"$inc" -c h_cxx.cpp -o h_cxx.o || fail "$h as $std"
    done
done
echo "ok"

step "pkg-config"
export PKG_CONFIG_PATH=$lib/pkgconfig
pkg-config --modversion pqp
pkg-config --cflags --libs pqp
# shellcheck disable=SC2046 # word splitting of pkg-config's flags is intended
"$cc" -std=c99 "${warn[@]}" src/consumer.c $(pkg-config --cflags --libs pqp) -lm -o consumer_pkg
readelf -d consumer_pkg | grep -q 'NEEDED.*\[libpqp\.so\.1\]' || fail "consumer_pkg does not need libpqp.so.1"
# The prefix is outside the loader's path: the rpath from the .pc file finds the library.
readelf -d consumer_pkg | grep -qE "(RPATH|RUNPATH).*\[$lib\]" || fail "consumer_pkg has no rpath to $lib"
env -u LD_LIBRARY_PATH ./consumer_pkg

step "-static \$(pkg-config --static --libs pqp): a static program"
# shellcheck disable=SC2046 # word splitting of pkg-config's flags is intended
"$cc" -std=c99 "${warn[@]}" src/consumer.c $(pkg-config --cflags pqp) -static \
    $(pkg-config --static --libs pqp) -o consumer_fully_static 2>static.log ||
    { cat static.log; fail "static link with pkg-config --static"; }
if readelf -d consumer_fully_static | grep -q NEEDED; then fail "consumer_fully_static needs a shared library"; fi
./consumer_fully_static

step "pkg-config --static, against libpqp.a"
static_libs=$(pkg-config --static --libs-only-l pqp | sed -e 's/-lpqp\b//')
echo "private libraries: $static_libs"
# shellcheck disable=SC2046,SC2086
"$cc" -std=c99 "${warn[@]}" src/consumer.c $(pkg-config --cflags pqp) "$lib/libpqp.a" $static_libs -o consumer_static_pkg
if readelf -d consumer_static_pkg | grep -q 'NEEDED.*libpqp'; then fail "consumer_static_pkg needs libpqp.so"; fi
./consumer_static_pkg

step "PQP 1.3 style: -I.. -L.. -lPQP"
"$cxx" -std=c++11 "${warn[@]}" src/legacy.cpp -I"$inc" -L"$lib" -lPQP -o legacy_lPQP
readelf -d legacy_lPQP | grep -q 'NEEDED.*\[libpqp\.so\.1\]' || fail "legacy_lPQP does not need libpqp.so.1"
LD_LIBRARY_PATH=$lib ./legacy_lPQP

step "PQP 1.3 programs with pkg-config, in every standard programs.txt lists"
while read -r name stds; do
    [[ -z $name || $name == \#* ]] && continue
    flags=()
    for w in $stds; do
        [[ $w == -* ]] && flags+=("$w")
    done
    for std in $stds; do
        [[ $std == -* ]] && continue
        # shellcheck disable=SC2046 # word splitting of pkg-config's flags is intended
        "$cxx" -std=c++$std "${warn[@]}" "${flags[@]}" -I"$harness" "$pqp13/$name.cpp" \
            $(pkg-config --cflags --libs pqp) -o "pqp13_${name}_$std" || fail "$name as c++$std"
        LD_LIBRARY_PATH=$lib "./pqp13_${name}_$std" | tail -n 1 | grep -q 'all checks passed' ||
            fail "$name as c++$std"
        echo "$name c++$std: ok"
    done
done <"$pqp13/programs.txt"

step "find_package(pqp) + PQP::PQP"
"$cmake" -S src -B cmake-build -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" \
    -DPQP13_DIR="$pqp13" -DPQP_HARNESS_DIR="$harness"
"$cmake" --build cmake-build
for exe in cmake-build/pqp13_*; do
    "$exe" | tail -n 1 | grep -q 'all checks passed' || fail "$exe (find_package)"
done
./cmake-build/consumer_c
./cmake-build/consumer_legacy
./cmake-build/consumer_static
if readelf -d cmake-build/consumer_static | grep -q 'NEEDED.*libpqp'; then fail "consumer_static needs libpqp.so"; fi

step "all consumer checks passed"
