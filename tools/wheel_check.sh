#!/bin/sh
# An installed opsrock runs its main job on its own: a wheel built from this checkout, installed (not
# editable) into a fresh venv, run from an empty folder outside the checkout. Called by `make test-wheel`.
#
# usage: tools/wheel_check.sh PYTHON LOCK
set -eu
python=$1
lock=$2
here=$(pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/opsrock-wheel-XXXXXX")
trap 'rm -rf "$work"' EXIT

"$python" -m venv "$work/venv"
"$work/venv/bin/python" -m pip install --quiet -c "$lock" pip
"$work/venv/bin/python" -m pip wheel --quiet --no-deps -w "$work/dist" "$here"
wheel=$(ls "$work"/dist/opsrock-*.whl)
"$work/venv/bin/python" -m pip install --quiet -c "$lock" "$wheel[records]"

mkdir "$work/empty"
cd "$work/empty"
opsrock=$work/venv/bin/opsrock
# the package is the installed one, not this checkout
"$work/venv/bin/python" -c "import opsrock, sys; sys.exit(0 if '$here' not in opsrock.__file__ else 1)"
"$opsrock" run tiny --out run --no-progress
test -s run/cases.csv
"$opsrock" validate --quick
test -s validation/closed_forms/closed_forms.csv
"$opsrock" reproduce --out out --no-progress
test -s out/report.md
echo "opsrock wheel check: run tiny, validate --quick and reproduce ran from an empty folder ($wheel)"
