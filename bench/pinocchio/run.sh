#!/usr/bin/env bash
# Pinocchio's side of rigid's benchmark (see BENCHMARKS.md).
#
#   bash bench/pinocchio/run.sh                 install, build, time every model; JSON lines on stdout
#   bash bench/pinocchio/run.sh --build-only    install and build only (bench/compare.py uses this)
#   bash bench/pinocchio/run.sh --reps 21 --states 1000   (any other argument goes to the timing program)
#
# Environment:
#   VARIANTS  builds to make and time, default "header lib":
#               header  Pinocchio's algorithms compiled here from its headers, -O3 -DNDEBUG (generic x86-64)
#               lib     the algorithms precompiled in the wheel's libpinocchio_default.so
#                       (-DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION, as Pinocchio's CMake target exports it)
#               native  as header, plus -march=native
#   PYTHON    python interpreter (default python3); CXX  C++ compiler (default g++)
#
# Steps: installs pin 4.1.0, example-robot-data 6.0.0 and cmeel-eigen from PyPI if they are not
# already there; exports the robots with Pinocchio's Python module (export_models.py); compiles
# timings.cpp against the headers and shared libraries under the wheel's cmeel.prefix (rpath set,
# objects cached in build/ by a hash of source, flags and compiler); runs it.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
BUILD="$HERE/build"
PY="${PYTHON:-python3}"
CXX="${CXX:-g++}"
VARIANTS="${VARIANTS:-header lib}"
BUILD_ONLY=0
ARGS=()
for a in "$@"; do
  case "$a" in
    --build-only) BUILD_ONLY=1 ;;
    *) ARGS+=("$a") ;;
  esac
done
log() { echo "[pinocchio] $*" >&2; }
mkdir -p "$BUILD"

# 1. Python packages (quiet and idempotent: pip runs only when a pinned version is missing)
need_install=0
for spec in pin==4.1.0 example-robot-data==6.0.0 cmeel-eigen; do
  name="${spec%%==*}"
  want="${spec#*==}"
  have="$("$PY" -c "import importlib.metadata as m, sys
try: print(m.version(sys.argv[1]))
except Exception: print('')" "$name")"
  if [[ -z "$have" || ( "$want" != "$spec" && "$have" != "$want" ) ]]; then need_install=1; fi
done
if [[ $need_install == 1 ]]; then
  log "installing pin==4.1.0 example-robot-data==6.0.0 cmeel-eigen from PyPI"
  "$PY" -m pip install -q --disable-pip-version-check "pin==4.1.0" "example-robot-data==6.0.0" cmeel-eigen >&2
fi

PREFIX="$("$PY" "$HERE/export_models.py" prefix)"
PIN_VERSION="$(sed -n 's/^# *define PINOCCHIO_VERSION "\(.*\)"/\1/p' "$PREFIX/include/pinocchio/config.hpp")"
log "Pinocchio $PIN_VERSION headers and libraries under $PREFIX"

# 2. models: URDF -> Pinocchio (Python) -> plain joint tree that timings.cpp rebuilds
"$PY" "$HERE/export_models.py" export "$BUILD/models" 2>"$BUILD/export.log" || {
  cat "$BUILD/export.log" >&2
  exit 1
}

# 3. compile: -O3 -DNDEBUG plus the definitions exported by Pinocchio's CMake config
# (lib/cmake/pinocchio/pinocchioTargets.cmake, target pinocchio::pinocchio_headers); the
# URDF parser, collision and serialization are not used, so neither urdfdom nor coal is needed.
COMMON=(-std=c++17 -O3 -DNDEBUG
  -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30
  -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12
  -I"$PREFIX/include" -I"$PREFIX/include/eigen3")
cflags_for() { # compile flags of a variant
  case "$1" in
    header) echo "" ;;
    native) echo "-march=native" ;;
    lib) echo "-DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION" ;;
    *) log "unknown variant $1"; exit 2 ;;
  esac
}
ldflags_for() { # link flags of a variant (rpath to the wheel's libraries)
  case "$1" in
    lib) echo "-L$PREFIX/lib -Wl,-rpath,$PREFIX/lib -lpinocchio_default" ;;
    *) echo "" ;;
  esac
}
for v in $VARIANTS; do cflags_for "$v" >/dev/null; done
# Five translation units per variant (timings.cpp: loading, states, output; timings-kin.cpp,
# timings-crba.cpp, timings-aba.cpp, timings-deriv.cpp: the algorithms), compiled in parallel on every core; each object is cached by
# a hash of its source, the shared header, the flags, Pinocchio's version and the compiler.
CXXID="$("$CXX" --version | head -1)"
compile_obj() { # variant unit
  local v="$1" u="$2" obj want t0
  obj="$BUILD/obj-$v/$u.o"
  want="$({ cat "$HERE/$u.cpp" "$HERE/timings.hpp"; echo "${COMMON[*]} $(cflags_for "$v") $PIN_VERSION $CXXID"; } | sha256sum | cut -c1-16)"
  if [[ -f "$obj" && -f "$obj.stamp" && "$(cat "$obj.stamp")" == "$want" ]]; then return 0; fi
  mkdir -p "$BUILD/obj-$v"
  t0=$(date +%s)
  # shellcheck disable=SC2046
  if ! "$CXX" "${COMMON[@]}" $(cflags_for "$v") -c "$HERE/$u.cpp" -o "$obj.tmp" 2>"$obj.log"; then
    log "compile $v/$u FAILED, see $obj.log"
    tail -20 "$obj.log" >&2
    return 1
  fi
  mv "$obj.tmp" "$obj"
  echo "$want" >"$obj.stamp"
  log "compiled $v/$u.cpp in $(($(date +%s) - t0)) s"
}
export -f compile_obj cflags_for log
export BUILD HERE CXX PIN_VERSION CXXID PREFIX
export COMMON_STR="${COMMON[*]}"
T0=$(date +%s)
JOBS="$(nproc 2>/dev/null || echo 2)"
# the heaviest units first, so that the cores stay busy to the end
for u in timings-deriv timings-aba timings-crba timings-kin timings; do for v in $VARIANTS; do echo "$v $u"; done; done |
  xargs -P "$JOBS" -L 1 bash -c 'COMMON=($COMMON_STR); compile_obj "$0" "$1"' || {
  log "build failed"
  exit 1
}
for v in $VARIANTS; do
  # shellcheck disable=SC2046
  "$CXX" -o "$BUILD/timings-$v" "$BUILD/obj-$v/timings.o" "$BUILD/obj-$v/timings-kin.o" \
    "$BUILD/obj-$v/timings-crba.o" "$BUILD/obj-$v/timings-aba.o" "$BUILD/obj-$v/timings-deriv.o" $(ldflags_for "$v")
done
log "builds ($VARIANTS) ready in $(($(date +%s) - T0)) s: $BUILD/timings-{${VARIANTS// /,}}"

[[ $BUILD_ONLY == 1 ]] && exit 0

# 4. run: every variant over every model, JSON lines on stdout
MODELS=()
while IFS=$'\t' read -r name _nq _nv _floating _src file; do
  MODELS+=("$name=$file")
done <"$BUILD/models/manifest.tsv"
for v in $VARIANTS; do
  "$BUILD/timings-$v" --build "$v" ${ARGS[@]+"${ARGS[@]}"} "${MODELS[@]}"
done
