#!/usr/bin/env bash
# Builds the editors' toolchain for tests/suite/plcopen_oracle.rs into DIR: matiec (iec2c) from source,
# Beremiz's sources and a Python environment for its generator. A few minutes; needs
# git mirrors or network access to github.com/beremiz, flex, bison, autotools, gcc.
#
#   tools/oracle/setup.sh DIR [MATIEC_SRC BEREMIZ_SRC]
#
# MATIEC_SRC and BEREMIZ_SRC may be existing source trees (copied) or git repositories,
# bare ones included (a mirror: cloned, its default branch checked out); otherwise both
# are cloned from GitHub.
set -euo pipefail
dir=$(mkdir -p "$1" && cd "$1" && pwd)
matiec_src=${2:-}
beremiz_src=${3:-}
need() { command -v "$1" >/dev/null || { echo "setup.sh: needs $1 (apt install $2)" >&2; exit 2; }; }
need flex flex; need bison bison; need autoreconf "autoconf automake libtool"; need gcc gcc; need python3 python3
fetch() { # name source
  if [ -e "$dir/$1" ]; then return; fi
  if [ -n "$2" ] && [ -f "$2/HEAD" ] && [ -d "$2/objects" ]; then # a bare repository
    git clone -q "$2" "$dir/$1"
  elif [ -n "$2" ]; then cp -a "$2" "$dir/$1"; else git clone --depth 1 "https://github.com/beremiz/$1" "$dir/$1"; fi
}
fetch matiec "$matiec_src"
fetch beremiz "$beremiz_src"
if [ ! -x "$dir/matiec/iec2c" ]; then
  (cd "$dir/matiec" && autoreconf -i && ./configure && make -j"$(nproc)") >"$dir/matiec-build.log" 2>&1 \
    || { echo "setup.sh: matiec did not build, see $dir/matiec-build.log" >&2; exit 1; }
fi
if [ ! -x "$dir/venv/bin/python" ]; then
  python3 -m venv "$dir/venv"
  # What PLCGenerator.py needs when loaded as Beremiz's command line loads it (fake_wx).
  "$dir/venv/bin/pip" install -q lxml future six click numpy matplotlib "zeroconf==0.62.0"
fi
echo "toolchain ready: II_ORACLE=$dir cargo test --release --test suite plcopen_oracle:: -- --ignored --nocapture"
