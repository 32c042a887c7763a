#!/usr/bin/env bash
# The Python package's tests, as ctest runs them (python/CMakeLists.txt):
#   python/run_tests.sh PYTHON BUILD_DIR
# Makes (or reuses) a virtual environment in BUILD_DIR/python-venv with PYTHON, installs the
# package from python/ as `pip install ./python` does (maturin, release profile; cargo's target
# directory in BUILD_DIR/python-cargo so rebuilds are incremental), pytest and the peers the tests
# compare against (python-fcl, trimesh with rtree and scipy for its proximity queries), then runs
# pytest. The exit status is pytest's.
set -euo pipefail

python=${1:?usage: run_tests.sh PYTHON BUILD_DIR}
build=${2:?usage: run_tests.sh PYTHON BUILD_DIR}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
venv="$build/python-venv"

if [[ ! -x "$venv/bin/python" ]]; then
    "$python" -m venv "$venv"
fi
pip=("$venv/bin/python" -m pip --disable-pip-version-check --quiet)
export CARGO_TARGET_DIR="$build/python-cargo"
"${pip[@]}" install numpy pytest python-fcl trimesh rtree scipy
# Built and reinstalled every run, so that it tracks the sources (cargo rebuilds only what
# changed); its one dependency, numpy, is installed above.
"${pip[@]}" install --force-reinstall --no-deps "$here"
"$venv/bin/python" -c 'import numpy, pqp; print("pqp", pqp.__version__, "numpy", numpy.__version__)'
cd "$here"
exec "$venv/bin/python" -m pytest -q -p no:cacheprovider tests
