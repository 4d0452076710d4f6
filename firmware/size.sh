#!/usr/bin/env bash
# The code-size tables of docs/firmware.md: .text and .rodata of small Cortex-M4F images
# (c_examples/bare-metal's startup and linker script, newlib) that each call one path of
# the library, at the Rust release profile's opt-level 3, "s" and "z" (LTO, one codegen
# unit, panic = abort, as in Cargo.toml), linked with --gc-sections. Prints Markdown tables:
#
#  1. the library with its default features (every scheme): one image per path;
#  2. one mesh scheme alone: the library built with only that scheme's Cargo feature
#     (linear), and with it and `mobius` (Möbius), each image calling that scheme.
#
# Table 1 takes one library build per opt-level, table 2 fifteen (eight schemes linear,
# seven Möbius: spherelike has no Möbius form), about 10 s each on two cores after the first;
# the whole run takes about 10 minutes. The staticlibs are cached in
# target/firmware/cargo-o<level> (cargo rebuilds only the ffi crate when the features
# change) and copied to target/firmware/size/lib-<features>-o<level>.a.
#
#   firmware/size.sh                 # both tables
#   firmware/size.sh loop kobbelt    # table 2 for these schemes only (and table 1)
#   SIZE_OPTS=3 firmware/size.sh     # opt-level 3 only (the other columns "—"; about 4 min)
#   SIZE_CHECK=1 firmware/size.sh    # also fails (exit 1) unless every one-scheme image is
#                                    # smaller than the image with every scheme
#
# scripts/test-firmware.sh runs SIZE_OPTS=3 SIZE_CHECK=1 (target/firmware/size-m4f.md).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
export PATH="$HOME/.cargo/bin:$PATH"
# The firmware configuration of firmware/build.sh: one core, no chunk-splitting paths.
export NLSUBDIV_MAX_CHUNKS=${NLSUBDIV_MAX_CHUNKS:-1}
OUT=$ROOT/target/firmware/size
mkdir -p "$OUT"
CPU="-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard"
BARE=$ROOT/c_examples/bare-metal
H=$ROOT/firmware/harness
read -ra OPTS <<<"${SIZE_OPTS:-3 s z}"

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

# Table 2: each scheme's Cargo feature, the scheme its image calls, and its name. The
# `akleman` feature holds Akleman's three schemes; its image calls the dual.
schemes=(loop catmull-clark butterfly kobbelt doo-sabin simplest akleman spherelike)
[ $# -gt 0 ] && schemes=("$@")
declare -A scode=(
    [loop]=NLS_SCHEME_LOOP [catmull-clark]=NLS_SCHEME_CATMULL_CLARK
    [butterfly]=NLS_SCHEME_MODIFIED_BUTTERFLY [kobbelt]=NLS_SCHEME_KOBBELT
    [doo-sabin]=NLS_SCHEME_DOO_SABIN [simplest]=NLS_SCHEME_SIMPLEST [akleman]=NLS_SCHEME_DUAL
    [spherelike]=NLS_SCHEME_SPHERELIKE
)
declare -A sname=(
    [loop]="Loop" [catmull-clark]="Catmull–Clark" [butterfly]="Modified Butterfly"
    [kobbelt]="Kobbelt" [doo-sabin]="Doo–Sabin" [simplest]="simplest"
    [akleman]="Akleman (dual; the feature holds all three)" [spherelike]="spherelike"
)

# section SIZE_A_OUTPUT NAME: the size of section NAME in `size -A` output.
section() { awk -v n="$2" '$1 == n { print $2 }' <<<"$1"; }

# library OPT FEATURES: builds libnlsubdiv.a at opt-level OPT with FEATURES ("default" for
# the default features, else a comma-separated list without the defaults) and prints the
# path of its copy.
library() {
    local opt=$1 features=$2 dir=$ROOT/target/firmware/cargo-o$1 flags=()
    [ "$features" != default ] && flags=(--no-default-features --features "$features")
    CARGO_PROFILE_RELEASE_OPT_LEVEL=$opt cargo rustc -q --release --locked -p nlsubdiv-ffi \
        --target thumbv7em-none-eabihf --target-dir "$dir" --crate-type staticlib "${flags[@]}"
    local copy=$OUT/lib-${features//,/+}-o$opt.a
    cp "$dir/thumbv7em-none-eabihf/release/libnlsubdiv.a" "$copy"
    echo "$copy"
}

# image NAME LIB DEFINES [LDFLAGS]: links the probe into $OUT/NAME.elf and prints the sizes
# of .text and .rodata.
image() {
    # shellcheck disable=SC2086  # the defines and flags are words
    arm-none-eabi-gcc $CPU -std=c99 -O2 -ffp-contract=off -ffunction-sections -fdata-sections \
        -I"$ROOT/include" -I"$H" $3 "$ROOT/firmware/size/probe.c" "$H/calls.c" "$H/arena.c" \
        "$BARE/startup.c" -nostartfiles -T "$BARE/link.ld" --specs=rdimon.specs -Wl,--gc-sections ${4:-} \
        "$2" -lm -o "$OUT/$1.elf" 2>/dev/null
    local sz
    sz=$(arm-none-eabi-size -A "$OUT/$1.elf")
    echo "$(section "$sz" .text) $(section "$sz" .rodata)"
}

declare -A text rodata
for opt in "${OPTS[@]}"; do
    lib=$(library "$opt" default)
    # every exported nls_ function kept as a root of --gc-sections
    keep=$(arm-none-eabi-nm -g --defined-only "$lib" 2>/dev/null | awk '$2 == "T" && $3 ~ /^nls_/ { printf " -Wl,--undefined=%s", $3 }')
    for p in "${probes[@]}"; do
        extra=""
        [ "$p" = all_exports ] && extra=$keep
        read -r text[$p,$opt] rodata[$p,$opt] < <(image "$p-o$opt" "$lib" "${defs[$p]}" "$extra")
    done
    for s in "${schemes[@]}"; do
        lib=$(library "$opt" "$s")
        read -r text[$s/linear,$opt] rodata[$s/linear,$opt] \
            < <(image "$s-linear-o$opt" "$lib" "-DPROBE_MESH=0 -DPROBE_SCHEME=${scode[$s]}")
        [ "$s" = spherelike ] && continue
        lib=$(library "$opt" "$s,mobius")
        read -r text[$s/mobius,$opt] rodata[$s/mobius,$opt] \
            < <(image "$s-mobius-o$opt" "$lib" "-DPROBE_MESH=NLS_SUBDIVIDE_MOBIUS -DPROBE_SCHEME=${scode[$s]}")
    done
done

# share KEY OPT: KEY's .text at OPT minus the baseline image's, "—" when not measured.
share() {
    local t=${text[$1,$2]:-}
    if [ -z "$t" ]; then echo "—"; else echo $((t - text[baseline,$2])); fi
}

echo "Default features (every scheme); bytes, opt-level 3, \"s\" and \"z\":"
echo
echo "| image (Cortex-M4F) | .text o3 | .text s | .text z | .rodata o3 | .rodata s | .rodata z |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for p in "${probes[@]}"; do
    printf "| %s | %s | %s | %s | %s | %s | %s |\n" "${what[$p]}" "${text[$p,3]:-—}" "${text[$p,s]:-—}" \
        "${text[$p,z]:-—}" "${rodata[$p,3]:-—}" "${rodata[$p,s]:-—}" "${rodata[$p,z]:-—}"
done
echo
echo "Library share (.text minus the baseline image's):"
echo
echo "| path | o3 | s | z |"
echo "|---|---:|---:|---:|"
for p in "${probes[@]:1}"; do
    printf "| %s | %s | %s | %s |\n" "${what[$p]}" "$(share "$p" 3)" "$(share "$p" s)" "$(share "$p" z)"
done
echo
echo "One mesh scheme alone: the library built with only its feature (linear), or with it and"
echo "\`mobius\` (Möbius); library share of .text (the image's minus the baseline's), bytes:"
echo
echo "| scheme (features) | linear o3 | linear s | linear z | Möbius o3 | Möbius s | Möbius z |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for s in "${schemes[@]}"; do
    features="\`$s\`"
    [ "$s" != spherelike ] && features="\`$s\`, \`$s,mobius\`"
    printf "| %s (%s) | %s | %s | %s | %s | %s | %s |\n" "${sname[$s]}" "$features" \
        "$(share "$s/linear" 3)" "$(share "$s/linear" s)" "$(share "$s/linear" z)" \
        "$(share "$s/mobius" 3)" "$(share "$s/mobius" s)" "$(share "$s/mobius" z)"
done
echo
echo "Largest .rodata of a one-scheme image (bytes): $(for k in "${!rodata[@]}"; do
    case $k in */*) echo "${rodata[$k]}" ;; esac
done | sort -n | tail -1)"

# Link only what you use: every one-scheme image below the image that reads the scheme at run
# time from a library with every scheme (docs/firmware.md, "Code size").
if [ "${SIZE_CHECK:-0}" = 1 ]; then
    bad=0
    for opt in "${OPTS[@]}"; do
        for k in "${!text[@]}"; do
            case $k in
                */*,"$opt")
                    if [ "${text[$k]}" -ge "${text[mesh_runtime,$opt]}" ]; then
                        echo "size check: ${k%,*} at opt-level $opt links ${text[$k]} bytes of .text," \
                            "not less than every scheme's ${text[mesh_runtime,$opt]}"
                        bad=1
                    fi ;;
            esac
        done
    done
    [ "$bad" -eq 0 ] || exit 1
    echo "size check: every one-scheme image is smaller than the image with every scheme"
fi
