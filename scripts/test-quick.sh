#!/usr/bin/env bash
# The quick tier: the checks to run before every commit, a few minutes on 2 cores once the
# build is warm (the first run builds the release tests and library; that takes longer).
#
#   scripts/test-quick.sh
#
# Formatting, clippy with warnings as errors, every Rust test of the workspace (release
# build: its tests run much faster than debug ones), the docs without broken links, the
# header freshness check, and every C suite under ASan+UBSan against the release staticlib. scripts/test-all.sh runs all of
# these and more (debug tests, docs, determinism across builds, valgrind, the panic-freedom
# proof, fuzzing, peers, integrations, the robustness dashboard).
#
# Logs are in target/test-quick/ (NLS_TEST_OUT elsewhere). Tests that cannot find the shared
# test meshes are listed and counted as skipped; the last line is
# "test-quick: N passed, M failed, K skipped" (scripts/lib-test.sh says how they count;
# NLS_SHARED_DATA names the meshes folder, NLS_REQUIRE_SHARED_DATA=1 fails without it).
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/lib-test.sh
run_begin test-quick

step "cargo fmt --check" cargo fmt --all -- --check
step "cargo clippy -D warnings" cargo clippy --workspace --all-targets --locked -- -D warnings
step "cargo test (release)" cargo test --workspace --locked --release --no-fail-fast
step "cargo doc (no broken links)" env RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked
header_fresh_step
step "build libnlsubdiv.a / .so (release)" cargo build --release --locked -p nlsubdiv-ffi
step "C tests under ASan+UBSan (gcc)" c_asan

run_end
