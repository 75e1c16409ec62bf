#!/usr/bin/env bash
# The Python package's tests: a virtual environment under target/ with
# pinned maturin, numpy, pytest and ray (for lumis.distributed's tests on
# a local Ray cluster); the CLI and the `lumis` wheel built
# from the library as `cargo test --workspace` compiles it (after that,
# only PyO3 and the native module are compiled), the wheel installed in
# the environment; then pytest.
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
RAY=2.60.0

stamp="$venv/.pins-$MATURIN-$NUMPY-$PYTEST-$RAY"
if [ ! -f "$stamp" ]; then
    rm -rf "$venv"
    "$py" -m venv "$venv"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
        "maturin==$MATURIN" "numpy==$NUMPY" "pytest==$PYTEST" "ray==$RAY"
    touch "$stamp"
fi

# The CLI exactly as `cargo test --workspace` builds it (the same feature
# resolution: building one of its tests, `cli`, builds the binary); after
# `cargo test` this is a no-op.
cargo test --workspace --no-run --test cli
# The wheel with the same compiled library: it cannot be built with
# `--profile test` (that would build a test harness), so it is built with
# `dev` at opt-level 3 with line tables only, which are the `test`
# profile's settings (Cargo.toml), in the same folder (target/debug);
# python/Cargo.toml turns on the features the test build resolves. Then
# only PyO3 and the native module are compiled.
rm -rf target/wheels/python-tests
log=target/wheels/python-tests.log
mkdir -p target/wheels
if ! CARGO_PROFILE_DEV_OPT_LEVEL=3 CARGO_PROFILE_DEV_DEBUG=line-tables-only \
    "$venv/bin/maturin" build --profile dev --strip \
    --manifest-path python/Cargo.toml --interpreter "$venv/bin/python" \
    --out target/wheels/python-tests >"$log" 2>&1; then
    cat "$log"
    exit 1
fi
if grep -q "Compiling lumis-render" "$log"; then
    echo "python-tests: the wheel compiled lumis-render again instead of reusing" \
        "the test build's: align the features listed in python/Cargo.toml" >&2
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-deps --force-reinstall target/wheels/python-tests/lumis-*.whl

export LUMIS_CLI="$root/target/debug/lumis"
# From another folder, so `import lumis` is the installed package, not
# python/lumis without its native module.
cd "$root/python/tests"
exec "$root/$venv/bin/python" -m pytest -p no:cacheprovider "$@"
