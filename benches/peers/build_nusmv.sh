#!/usr/bin/env bash
# Builds NuSMV 2.5.4 (the peer of benches/plants.py) from the sources the `pynusmv`
# sdist on PyPI bundles, into ${NUSMV_HOME:-$HOME/.cache/ii-prove-peers}. Prints the
# path of the NuSMV binary. About 3 minutes on 2 cores; nothing is built if it exists.
set -euo pipefail
home="${NUSMV_HOME:-$HOME/.cache/ii-prove-peers}"
bin="$home/pynusmv-1.0rc8/dependencies/NuSMV/NuSMV-2.5.4/nusmv/NuSMV"
if [ -x "$bin" ]; then echo "$bin"; exit 0; fi
if ! command -v bison >/dev/null || ! command -v flex >/dev/null; then
    apt-get update -qq >&2 && apt-get install -y -qq bison flex >&2
fi
mkdir -p "$home" && cd "$home"
pip download --quiet --no-deps --pre pynusmv==1.0rc8 -d . >&2
tar xzf pynusmv-1.0rc8.tar.gz
cd pynusmv-1.0rc8/dependencies/MiniSat
make minisat.patched >&2
sed -i 's/extern "C"\([a-zA-Z]\)/extern "C" \1/' minisat/simp/Solver_C.C
make -C minisat >&2
cd ../NuSMV
tar -xpf NuSMV-2.5.4.tar.gz
patch -p0 -N < pynusmv.patch >&2
patch -p0 -N < cudd.patch >&2
sed -i 's/^    union wait status;/    int status;/' NuSMV-2.5.4/cudd-2.4.1.1/util/pipefork.c
cd NuSMV-2.5.4/nusmv
./configure --enable-minisat --with-minisat-libdir=../../../MiniSat/minisat \
    --with-minisat-incdir=../../../MiniSat/minisat \
    CFLAGS="-g -O2 -fPIC -fcommon -std=gnu89 -Wno-implicit-function-declaration -Wno-int-conversion -Wno-incompatible-pointer-types" >&2
make -j2 >&2
echo "$bin"
