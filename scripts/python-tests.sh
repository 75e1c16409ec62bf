#!/usr/bin/env bash
# The Python package's tests: a virtual environment under target/ with
# pinned maturin, numpy and pytest; the CLI and the `lumis` wheel built
# with the `test` profile's settings (opt-level 3) in the workspace's
# target/, the wheel installed in the environment; then pytest.
#
#   bash scripts/python-tests.sh [pytest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
venv=target/python-venv
py=${PYTHON:-python3}

# Pinned so a run does not change under us; bump deliberately.
MATURIN=1.16.0
NUMPY=2.4.6
PYTEST=9.2.0

stamp="$venv/.pins-$MATURIN-$NUMPY-$PYTEST"
if [ ! -f "$stamp" ]; then
    rm -rf "$venv"
    "$py" -m venv "$venv"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
        "maturin==$MATURIN" "numpy==$NUMPY" "pytest==$PYTEST"
    touch "$stamp"
fi

# The CLI and the wheel share one compile of the library: the wheel cannot
# be built with `--profile test` (that builds a test harness), so it is
# built with `dev` at opt-level 3, which are the `test` profile's settings
# (Cargo.toml), hence the same compiled dependencies in the same folder
# (target/debug). (What `cargo test --workspace` compiled is not reused:
# the test build unifies features that dev-dependencies enable, such as
# serde's `alloc`, into the library's dependencies, so its artifacts differ.)
cargo build --profile test -p lumis
rm -rf target/wheels/python-tests
CARGO_PROFILE_DEV_OPT_LEVEL=3 "$venv/bin/maturin" build --profile dev --strip \
    --manifest-path python/Cargo.toml --interpreter "$venv/bin/python" \
    --out target/wheels/python-tests --quiet
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-deps --force-reinstall target/wheels/python-tests/lumis-*.whl

export LUMIS_CLI="$root/target/debug/lumis"
# From another folder, so `import lumis` is the installed package, not
# python/lumis without its native module.
cd "$root/python/tests"
exec "$root/$venv/bin/python" -m pytest -p no:cacheprovider "$@"
