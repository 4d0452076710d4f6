#!/usr/bin/env bash
# The code-size table of docs/firmware.md: .text and .rodata of small Cortex-M4F images
# (c_examples/bare-metal's startup and linker script, newlib) that each call one path of
# the library, at the Rust release profile's opt-level 3, "s" and "z" (LTO, one codegen
# unit, panic = abort, as in Cargo.toml), linked with --gc-sections. Prints a Markdown table;
# the staticlibs are cached in target/firmware/cargo-o<level>.
#
#   firmware/size.sh
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
export PATH="$HOME/.cargo/bin:$PATH"
OUT=$ROOT/target/firmware/size
mkdir -p "$OUT"
CPU="-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard"
BARE=$ROOT/c_examples/bare-metal
H=$ROOT/firmware/harness

probes=(baseline f4 curve mesh_linear mesh_mobius mesh_runtime all_exports)
declare -A what=(
    [baseline]="start-up, newlib init, nls_version only"
    [f4]="nls_f4"
    [curve]="one curve scheme (Möbius interpolating)"
    [mesh_linear]="one mesh scheme: Loop, linear"
    [mesh_mobius]="one mesh scheme: Loop, Möbius"
    [mesh_runtime]="mesh, scheme and flags read at run time"
    [all_exports]="every export of the C ABI"
)
declare -A defs=(
    [baseline]=-DPROBE_BASELINE [f4]=-DPROBE_F4 [curve]=-DPROBE_CURVE [mesh_linear]=-DPROBE_MESH=0
    [mesh_mobius]=-DPROBE_MESH=NLS_SUBDIVIDE_MOBIUS [mesh_runtime]="-DPROBE_MESH=0 -DPROBE_RUNTIME"
    [all_exports]=-DPROBE_BASELINE
)

# section SIZE_A_OUTPUT NAME: the size of section NAME in `size -A` output.
section() { awk -v n="$2" '$1 == n { print $2 }' <<<"$1"; }

declare -A text rodata
for opt in 3 s z; do
    dir=$ROOT/target/firmware/cargo-o$opt
    CARGO_PROFILE_RELEASE_OPT_LEVEL=$opt cargo rustc -q --release --locked -p nlsubdiv-ffi \
        --target thumbv7em-none-eabihf --target-dir "$dir" --crate-type staticlib
    lib=$dir/thumbv7em-none-eabihf/release/libnlsubdiv.a
    # every exported nls_ function kept as a root of --gc-sections
    keep=$(arm-none-eabi-nm -g --defined-only "$lib" 2>/dev/null | awk '$2 == "T" && $3 ~ /^nls_/ { printf " -Wl,--undefined=%s", $3 }')
    for p in "${probes[@]}"; do
        extra=""
        [ "$p" = all_exports ] && extra=$keep
        # shellcheck disable=SC2086
        arm-none-eabi-gcc $CPU -std=c99 -O2 -ffp-contract=off -ffunction-sections -fdata-sections \
            -I"$ROOT/include" -I"$H" ${defs[$p]} "$ROOT/firmware/size/probe.c" "$H/calls.c" "$H/arena.c" \
            "$BARE/startup.c" -nostartfiles -T "$BARE/link.ld" --specs=rdimon.specs -Wl,--gc-sections $extra \
            "$lib" -lm -o "$OUT/$p-o$opt.elf" 2>/dev/null
        sz=$(arm-none-eabi-size -A "$OUT/$p-o$opt.elf")
        text[$p,$opt]=$(section "$sz" .text)
        rodata[$p,$opt]=$(section "$sz" .rodata)
    done
done

echo "| image (Cortex-M4F) | .text o3 | .text s | .text z | .rodata o3 | .rodata s | .rodata z |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for p in "${probes[@]}"; do
    printf "| %s | %s | %s | %s | %s | %s | %s |\n" "${what[$p]}" "${text[$p,3]}" "${text[$p,s]}" "${text[$p,z]}" \
        "${rodata[$p,3]}" "${rodata[$p,s]}" "${rodata[$p,z]}"
done
echo
echo "Library share (.text minus the baseline image's):"
echo "| path | o3 | s | z |"
echo "|---|---:|---:|---:|"
for p in "${probes[@]:1}"; do
    printf "| %s | %d | %d | %d |\n" "${what[$p]}" $((text[$p,3]-text[baseline,3])) \
        $((text[$p,s]-text[baseline,s])) $((text[$p,z]-text[baseline,z]))
done
