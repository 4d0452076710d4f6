#!/usr/bin/env python3
"""Static call-graph stack bound of the Cortex-M4F harness (docs/firmware.md, "Stack").

The painted measurement of scripts/test-firmware.sh sees only the paths the test cases take;
this bound covers every path the code has. For each entry point of the harness (the names of
firmware/stack-bounds.txt) it prints the most bytes of stack below the case's stack pointer
any path can use, and the deepest path.

    firmware/stack_bound.py ELF [--stack-sizes-elf ELF2] [--llvm-ir IR.ll] [--run RUN.txt]
                                [--bounds FILE] [--paths] [--indirect] [--drop-type NAME]

ELF is the harness to bound: the M4F build that scripts/test-firmware.sh runs and measures.
ELF2 is the same harness with its Rust library built by nightly with -Z emit-stack-sizes
(`firmware/build.sh m4f-stack-sizes`), whose .stack_sizes section holds the compiler's frame
size of every Rust function.

Frames. A function's frame is what its disassembly allocates: the sum of every stack-pointer
decrement in its body (push, stmdb sp!, vpush, vstmdb sp!, sub sp, str ... [sp, #-n]!).
Summing the whole body rather than the first block is an over-estimate when a function has
two prologues on two paths, and never an under-estimate; a decrement by a register or sp
set from a register makes the function's frame UNKNOWN. The method is checked on ELF2: it
must give the .stack_sizes figure of every Rust function there (else the run fails), and it
is what sizes the functions that have no entry (compiler-builtins' soft-float __aeabi_*, the
C harness, newlib, libgcc) and every function of the stable build, which has no .stack_sizes.
Where ELF has a .stack_sizes entry, that entry is the frame.

Call graph. From `arm-none-eabi-objdump -d`: bl, and every branch (b, b.w, bcc.w) whose
target lies outside the function is an edge (a tail call; the caller's frame is counted too,
although it was popped: an over-estimate). Indirect calls and branches (blx rN, bx rN other
than lr, mov pc / ldr pc other than returns) are resolved by type from IR.ll, the LLVM IR of
ELF's Rust library after LTO (`firmware/build.sh m4f-llvm-ir`: the same stable build with
--emit=llvm-ir added, so its functions are ELF's, inlining done, named by the same mangled
symbols). An indirect call of the IR (a `dyn Trait` method through its vtable: the passes'
`exec.run(...)` on `&dyn Executor`, their `&dyn Fn` tasks; a fn pointer: the curve rules)
can reach every function whose address the IR takes (a use of @f other than as a direct
callee: vtable constants, stores, arguments) with the call's return type and parameter
types (an sret parameter marked): every function of that type that any vtable slot or fn
pointer can hold, a sound over-approximation. An ELF function gets the union over its IR
call sites; a candidate that is not in ELF was removed by the linker, so nothing points to
it. A function with indirect sites that is not in the IR (C, newlib, compiler-builtins), or
whose IR body has no indirect call, or one of whose IR calls matches no address-taken
function's type, stays unresolved, as does every one without IR.ll.
RESOLVED below overrides by hand, per function, with the reason. An indirect call that is
reachable from an entry point and not resolved makes that entry point's bound UNKNOWN, never
0. --drop-type NAME ignores the IR's targets of the functions whose name contains NAME: a
bound that then falls below a painted mark shows the resolution is what covers that path
(curve subdivide: 3,656 -> 1,080 bytes, below its mark of 3,064, with NAME run_levels).

Worst path. worst(f) = frame(f) + max over callees c of worst(c), memoised (each function is
visited once: linear in the size of the graph). A cycle on the call graph is recursion: it is
reported by name and makes the bound of every entry point that reaches it UNKNOWN, unless it
is a direct recursion bounded by construction, listed in BOUNDED_RECURSION with its depth, or
a mutual one walked at most once, listed in BOUNDED_CYCLES.

The harness's part. A case's mark also holds what the harness calls between the painting and
the measurement (fw_case_begin_at, the hashing and checks, the soft-float operations of the
checks, fw_case_end up to fw_stack_used): every entry point's bound is at least the deepest of
those.

Exit status: 0 when the frame method agrees with .stack_sizes, every bound is at least the
measured high-water mark of RUN.txt (a lower static bound means the analysis is wrong) and at
most the entry's ceiling in FILE (firmware/stack-static-bounds.txt), and every entry point
that is UNKNOWN is listed as UNKNOWN there; 1 otherwise; 2 on a usage error.
"""

import argparse
import re
import struct
import subprocess
import sys

# The functions an entry point's cases call between the painting (fw_case_begin) and the
# measurement (fw_case_end): the C ABI function named like the entry point, or the adapter of
# firmware/harness/calls.c the case calls for a scheme group.
GROUP_ROOTS = [
    (re.compile(r"^mesh .* tagged \((linear|Möbius)\)$"), ["fw_mesh_subdivide_tagged"]),
    (re.compile(r"^mesh options \(Möbius\)$"), ["fw_mesh_subdivide_spectrum"]),
    (re.compile(r"^mesh .* \((linear|Möbius)\)$"), ["fw_mesh_subdivide"]),
    (re.compile(r"^curve subdivide$"), ["fw_curve_subdivide"]),
    (re.compile(r"^differential subdivide$"), ["fw_differential_subdivide"]),
    (re.compile(r"^star rules$"), ["fw_loop_star", "fw_catmull_clark_star", "fw_butterfly_star"]),
    (re.compile(r"^(nls_\w+)$"), None),  # the C ABI function itself
]

# Callees of the case functions that run outside the measured window (before the painting or
# after the measurement), so they are not part of any entry point's bound.
OUTSIDE_WINDOW = {"snprintf", "printf", "puts", "putchar", "fw_case_end", "fw_meshes_init", "fw_fail", "fw_note_pass"}

# Indirect calls and branches resolved by hand: function -> (targets, why); these take the
# place of the LLVM IR's resolution by type (--llvm-ir) for the functions they name. The IR
# cannot see the C side: the only call from the library into a C pointer is the host
# executor's, and the harness sets none.
RESOLVED = {
    "<nlsubdiv::executor::HostExecutor as nlsubdiv::exec::Executor>::run": (
        [], "the host's run callback (nls_executor.run): the harness sets no executor, so the "
            "library runs its passes on the serial executor and never calls a host function"),
    "raise": ([], "a signal handler: the harness installs none (signal is never called), so abort's "
                  "raise takes the default action"),
}

# Recursion that is bounded by construction: a function (by a part of its name) that calls
# itself directly -> (most activations on one path, why). Its own frame counts that many
# times, its other callees once, below the deepest activation. Any other cycle is UNKNOWN.
# None today: the multigrid V-cycle of differential subdivision, which recursed once per
# hierarchy level, is a loop (src/differential/solve/multigrid.rs).
BOUNDED_RECURSION: dict = {}

# Mutual recursion bounded by construction: caller -> (callee, why): the callee, called from
# caller, cannot call caller again, so that edge leads to a copy of the callee without its
# edge back to caller (the cycle is walked at most once: callee > caller > callee).
BOUNDED_CYCLES = {
    "_stat": ("_swiopen", "newlib's semihosting open (libgloss/arm): _swiopen calls _stat only when its "
                          "flags hold O_CREAT|O_EXCL (and.w r3, r6, #0xa00; cmp; beq), and _stat calls "
                          "_swiopen with flags 0 (movs r1, #0): panics reach it through abort > _exit"),
}

CONDS = "eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le|al"
BRANCH = re.compile(rf"^(bl|b)({CONDS})?(\.w|\.n)?$")
INSN = re.compile(r"^\s+([0-9a-f]+):\t(\S+)\s*(.*)$")
HEADER = re.compile(r"^([0-9a-f]+) <(.*)>:$")
TARGET = re.compile(r"^([0-9a-f]+) <")


def elf_sections(data):
    """(name -> (addr, offset, size)) and the symbol table's function symbols
    (start address -> (name, size)) of a 32-bit little-endian ELF."""
    if data[:4] != b"\x7fELF" or data[4] != 1 or data[5] != 1:
        raise SystemExit("stack_bound: not a 32-bit little-endian ELF")
    shoff, = struct.unpack_from("<I", data, 0x20)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x2E)
    headers = [struct.unpack_from("<IIIIIIIIII", data, shoff + i * shentsize) for i in range(shnum)]
    strtab = headers[shstrndx]

    def name_at(table, off):
        start = table[4] + off
        return data[start:data.index(b"\0", start)].decode()

    sections = {name_at(strtab, h[0]): (h[3], h[4], h[5], h[1], h[2]) for h in headers}
    funcs, names_all = {}, {}
    for h in headers:
        if h[1] != 2:  # SHT_SYMTAB
            continue
        names = headers[h[6]]
        for i in range(h[5] // 16):
            st_name, value, size, info, _, _ = struct.unpack_from("<IIIBBH", data, h[4] + i * 16)
            if info & 0xF == 2:  # STT_FUNC
                funcs.setdefault(value & ~1, (name_at(names, st_name), size))
                names_all.setdefault(name_at(names, st_name), value & ~1)
    elf_sections.names = names_all  # every function symbol (aliases too) -> address
    return sections, funcs


def stack_sizes(data, sections):
    """address -> frame bytes, from .stack_sizes: (u32 address, ULEB128 size) pairs."""
    out = {}
    if ".stack_sizes" not in sections:
        return out
    _, off, size, _, _ = sections[".stack_sizes"]
    pos, end = off, off + size
    while pos < end:
        addr, = struct.unpack_from("<I", data, pos)
        pos += 4
        value = shift = 0
        while True:
            byte = data[pos]
            pos += 1
            value |= (byte & 0x7F) << shift
            shift += 7
            if byte < 0x80:
                break
        out[addr & ~1] = value
    return out


def reg_count(regs):
    """Bytes of a register list: {r4, r5, lr} 4 each, {d8-d15} 8 each, {s16-s31} 4 each."""
    total = 0
    for item in regs.strip("{} ").split(","):
        item = item.strip()
        m = re.match(r"^([rds])(\d+)-[rds](\d+)$", item)
        if m:
            n = int(m.group(3)) - int(m.group(2)) + 1
            total += n * (8 if m.group(1) == "d" else 4)
        elif item.startswith("d"):
            total += 8
        elif item:
            total += 4
    return total


def sp_decrement(mnem, ops):
    """Bytes by which one instruction lowers sp: an int, None (does not lower it) or "dynamic"."""
    base = mnem.split(".")[0]
    ops = ops.split("@")[0].strip()
    if base in ("push", "vpush"):
        return reg_count(ops)
    if base in ("stmdb", "stmfd", "vstmdb") and ops.startswith("sp!"):
        return reg_count(ops[ops.index("{"):])
    if base in ("sub", "subw"):
        m = re.match(r"^sp,\s*(?:sp,\s*)?#(\d+)$", ops)
        if m:
            return int(m.group(1))
        if re.match(r"^sp,\s*(?:sp,\s*)?r\w+", ops):
            return "dynamic"
    if base.startswith("str"):
        m = re.search(r"\[sp,\s*#-(\d+)\]!$", ops)
        if m:
            return int(m.group(1))
    if base == "mov" and re.match(r"^sp,\s*r\d+$", ops):
        # sp from a register (a realigned frame, or a restore the method cannot tell from one):
        # not a size the disassembly gives. LLVM and GCC restore sp by add/sub and pop here.
        return "dynamic"
    return None


def disassemble(elf, funcs):
    """name/address maps and, per function start: its body's frame by the prologue method,
    direct callees, indirect sites."""
    text = subprocess.run(["arm-none-eabi-objdump", "-d", "--no-show-raw-insn", "-C", elf],
                          check=True, capture_output=True, text=True).stdout
    starts = sorted(funcs)
    info = {}
    cur = None
    for line in text.splitlines():
        h = HEADER.match(line)
        if h:
            addr = int(h.group(1), 16)
            if addr in funcs:
                cur = {"name": h.group(2), "raw": funcs[addr][0], "start": addr, "end": addr + max(funcs[addr][1], 2),
                       "frame": 0, "dynamic": False, "callees": set(), "indirect": [],
                       "rust": funcs[addr][0].startswith(("_R", "_ZN"))}
                info[addr] = cur
            continue
        m = INSN.match(line)
        if not m or cur is None:
            continue
        pc, mnem, ops = int(m.group(1), 16), m.group(2), m.group(3)
        if not cur["start"] <= pc < cur["end"]:
            continue
        d = sp_decrement(mnem, ops)
        if d == "dynamic":
            cur["dynamic"] = True
        elif d:
            cur["frame"] += d
        if mnem.startswith("."):
            continue
        b = BRANCH.match(mnem)
        t = TARGET.match(ops)
        if b and t:
            target = int(t.group(1), 16)
            if b.group(1) == "bl" or not cur["start"] <= target < cur["end"]:
                cur["callees"].add(target)
            continue
        reg = ops.split(",")[0].strip()
        if mnem.startswith("blx") and reg.startswith("r"):
            cur["indirect"].append(f"{pc:x}: {mnem} {ops}")
        elif mnem.startswith("bx") and reg != "lr":
            cur["indirect"].append(f"{pc:x}: {mnem} {ops}")
        elif re.match(r"^(mov|ldr)(\.w)?$", mnem) and reg == "pc" and not ops.startswith("pc, [sp], #"):
            cur["indirect"].append(f"{pc:x}: {mnem} {ops}")
    # a branch into the middle of a function (shared tails, e.g. newlib's) is a call of the
    # function that holds the target
    import bisect
    for f in info.values():
        resolved = set()
        for t in f["callees"]:
            i = bisect.bisect_right(starts, t) - 1
            if i >= 0 and starts[i] in info:
                resolved.add(starts[i])
            else:
                f["indirect"].append(f"branch to {t:x}, in no known function")
        f["callees"] = resolved
    return info


IR_NAME = r'(?:"(?:[^"\\]|\\.)*"|[-\w.$]+)'
IR_DEFINE = re.compile(rf'^(define|declare)\b[^@]*@({IR_NAME})\(')
IR_ALIAS = re.compile(rf'^@({IR_NAME}) = .*\balias\b.*, ptr @({IR_NAME})\s*$')
IR_INDIRECT = re.compile(r'\bcall\b[^@]*?\s(%[-\w.$]+)\(')
IR_GLOBAL = re.compile(rf'@({IR_NAME})(\(?)')


def ir_types(text):
    """The type of each argument of an LLVM argument or parameter list (the text between the
    parentheses): the first type of each comma-separated item, brackets kept whole."""
    out, depth, item = [], 0, ""
    for ch in text + ",":
        if ch in "({[<":
            depth += 1
        elif ch in ")}]>":
            depth -= 1
        if ch == "," and depth == 0:
            item = item.strip()
            if item and item != "...":
                m = re.match(r"^(\{.*?\}|\[.*?\]|<.*?>|\S+)", item)
                # sret is the ABI's return slot: a call passes it where the callee has it
                out.append(m.group(1) + (" sret" if " sret(" in item else ""))
            elif item == "...":
                out.append("...")
            item = ""
        else:
            item += ch
    return tuple(out)


def ir_return(before):
    """The return type that ends the text before a function's name (define, declare, call)."""
    before = before.rstrip()
    if before.endswith(("}", "]", ">")):
        depth = 0
        for i in range(len(before) - 1, -1, -1):
            depth += before[i] in "}]>"
            depth -= before[i] in "{[<"
            if depth == 0:
                return before[i:]
    return before.split()[-1] if before.split() else ""


def balanced(line, start):
    """The text between the parenthesis at line[start] and its match."""
    depth = 0
    for i in range(start, len(line)):
        depth += line[i] == "("
        depth -= line[i] == ")"
        if depth == 0:
            return line[start + 1:i]
    return line[start + 1:]


def resolve_by_type(ll_path, info, names):
    """Indirect calls resolved from the LLVM IR of the same Rust library build (after LTO: the
    functions of the IR are those of the ELF, inlining done). The targets of an indirect call
    of the IR (a `dyn Trait` method through its vtable, a `&dyn Fn` task, a fn pointer) are
    every function whose address the IR takes (any use of @f other than as a direct callee:
    vtable constants, stores, arguments) and whose parameter types are those of the call: a
    sound over-approximation of what any vtable slot or fn pointer of that type can hold.
    ELF function -> (target addresses, candidate names, why) for every Rust function of ELF
    that has indirect sites; a function not in the IR, or with no indirect call in its IR
    body, is left unresolved (UNKNOWN)."""
    unquote = lambda n: n[1:-1] if n.startswith('"') else n
    params, sites, taken, alias = {}, {}, set(), {}
    cur = None
    with open(ll_path, encoding="utf-8") as fh:
        for line in fh:
            m = IR_DEFINE.match(line)
            if m:
                name = unquote(m.group(2))
                at = line.index("@" + m.group(2) + "(")
                params[name] = (ir_return(line[:at]),) + ir_types(balanced(line, m.end() - 1))
                if m.group(1) == "define":
                    cur = name
                    sites[cur] = []
                continue
            if line.startswith("}"):
                cur = None
                continue
            m = IR_ALIAS.match(line)
            if m:
                alias[unquote(m.group(1))] = unquote(m.group(2))
            if line.startswith(("!", "attributes ", ";")):
                continue
            for c in IR_INDIRECT.finditer(line) if cur else ():
                sites[cur].append((ir_return(line[:c.start(1)]),) + ir_types(balanced(line, c.end() - 1)))
            # A global followed by "(" right after "call ..." is a direct callee; any other use
            # of a function's name takes its address.
            for g in IR_GLOBAL.finditer(line):
                if not g.group(2) or not re.search(r"\bcall\b[^@]*$", line[:g.start()]):
                    taken.add(unquote(g.group(1)))
    for a, b in alias.items():
        params.setdefault(a, params.get(b))
    by_key = {}
    for f in taken:
        if f in params and params[f] is not None:
            by_key.setdefault(params[f], set()).add(f)
    out = {}
    for f in info.values():
        if not f["indirect"]:
            continue
        raw = f["raw"]
        if raw not in sites:
            continue  # not a function of the Rust library's IR: stays unresolved
        if not sites[raw]:
            continue  # an indirect branch the IR does not have (codegen's own): unresolved
        cands, empty = set(), [key for key in sites[raw] if not by_key.get(key)]
        if empty:
            # a call whose type no address-taken function has: the method cannot tell what it
            # reaches (a cast pointer, a type it parses wrongly), so it stays unresolved
            continue
        for key in sites[raw]:
            cands |= by_key[key]
        targets = {names[c] for c in cands if c in names} | \
                  {names[alias[c]] for c in cands if c in alias and alias[c] in names}
        # a candidate that is in neither the ELF nor an alias of one of its functions was
        # removed by the linker (--gc-sections): nothing references it, so no pointer to it
        # exists at run time.
        out[f["start"]] = (targets, sorted(cands),
                           f"{len(sites[raw])} indirect call(s) in the IR, {len(cands)} candidate(s) "
                           f"of their types, {len(targets)} in the ELF")
    return out


def analyse(info, sizes, by_type=None, drop=None):
    """Per function: (worst bytes or None, deepest path as addresses, why unknown)."""
    by_name = {f["name"]: a for a, f in info.items()}
    for name, (targets, _why) in RESOLVED.items():
        if name in by_name:
            f = info[by_name[name]]
            f["callees"] |= {by_name[t] for t in targets if t in by_name}
            f["indirect"] = []
    # the LLVM IR's resolution (resolve_by_type), where RESOLVED says nothing; --drop-type
    # removes the candidates of the functions it names (a check that the resolution matters)
    hand = {by_name[n] for n in RESOLVED if n in by_name}
    for a, (targets, _cands, _why) in (by_type or {}).items():
        if a in hand:
            continue
        f = info[a]
        if not (drop and drop in f["name"]):
            f["callees"] |= targets
        f["indirect"] = []
    for caller, (callee, _why) in BOUNDED_CYCLES.items():
        if caller in by_name and callee in by_name:
            a, b = by_name[caller], by_name[callee]
            clone = dict(info[b], name=f"{callee} (called by {caller})", callees=info[b]["callees"] - {a})
            info[-b] = clone  # a negative address: no .stack_sizes entry, the prologue frame
            info[a]["callees"] = info[a]["callees"] - {b} | {-b}
    sys.setrecursionlimit(100000)
    memo, onstack = {}, []
    cycles = []

    def frame(a):
        if a in sizes:
            return sizes[a], None
        f = info[a]
        if f["dynamic"]:
            return None, f"{f['name']}: variable-length frame"
        return f["frame"], None

    def worst(a):
        if a in memo:
            return memo[a]
        if a in onstack:
            cyc = onstack[onstack.index(a):] + [a]
            cycles.append(" -> ".join(info[c]["name"] for c in cyc))
            return (None, [a], "recursion: " + cycles[-1])
        onstack.append(a)
        f = info[a]
        own, why = frame(a)
        callees = f["callees"]
        for part, (depth, _why) in BOUNDED_RECURSION.items():
            if part in f["name"] and a in callees and own is not None:
                own, callees = own * depth, callees - {a}
        best, path, unknown = 0, [], why
        if f["indirect"] and not unknown:
            unknown = f"{f['name']}: unresolved indirect call ({f['indirect'][0]})"
        for c in sorted(callees):
            w, p, u = worst(c)
            if u and not unknown:
                unknown = u
            if w is not None and w > best:
                best, path = w, p
        onstack.pop()
        result = (None if unknown else own + best, [a] + path, unknown)
        memo[a] = result
        return result

    return worst, by_name, cycles


def measured(run):
    """entry -> largest measured high-water mark of the M4F run log."""
    out = {}
    with open(run, encoding="utf-8") as fh:
        for line in fh:
            if line.startswith("stack "):
                entry, _case, value = line[6:].rstrip("\n").split("\t")
                out[entry] = max(out.get(entry, -1), int(value))
    return out


def read_bounds(path):
    """entry -> bytes (None for UNKNOWN), in the file's order (tab-separated, # comments)."""
    out = {}
    with open(path, encoding="utf-8") as fh:
        for line in fh:
            line = line.rstrip("\n")
            if line and not line.startswith("#"):
                entry, value = line.split("\t")
                out[entry] = None if value == "UNKNOWN" else int(value)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("elf", help="the harness to bound (the M4F ELF that the run measured)")
    ap.add_argument("--stack-sizes-elf", help="the same harness built with -Z emit-stack-sizes "
                    "(firmware/build.sh m4f-stack-sizes): checks the prologue method (default: ELF)")
    ap.add_argument("--run", help="the M4F run log (stack lines) to check the bounds against")
    ap.add_argument("--bounds", help="entry -> ceiling of the static bound (tab-separated)")
    ap.add_argument("--entries", default="firmware/stack-bounds.txt",
                    help="the entry points (first column of this file)")
    ap.add_argument("--llvm-ir", help="the LLVM IR of the Rust library of ELF, after LTO "
                    "(firmware/build.sh m4f-llvm-ir): resolves its indirect calls by type")
    ap.add_argument("--drop-type", metavar="NAME", help="a check of the check: ignore the IR's "
                    "targets of the indirect calls of the functions whose name contains NAME")
    ap.add_argument("--paths", action="store_true", help="print each deepest path in full")
    ap.add_argument("--indirect", action="store_true",
                    help="list every unresolved indirect call reachable from the entry points")
    args = ap.parse_args()
    args.stack_sizes_elf = args.stack_sizes_elf or args.elf

    # The prologue method checked against the compiler's own frame sizes, on the build that
    # has them: every Rust function must agree, or the method is wrong and so is any bound.
    data = open(args.stack_sizes_elf, "rb").read()
    sections, funcs = elf_sections(data)
    sizes = stack_sizes(data, sections)
    if not sizes:
        print(f"stack_bound: {args.stack_sizes_elf} has no .stack_sizes section "
              "(build it with firmware/build.sh m4f-stack-sizes)")
        return 1
    info = disassemble(args.stack_sizes_elf, funcs)
    sizes = {a: v for a, v in sizes.items() if a in info}
    agree = [a for a in sizes if not info[a]["dynamic"] and info[a]["frame"] == sizes[a]]
    differ = sorted((a for a in sizes if a not in agree), key=lambda a: info[a]["name"])
    print(f"frames: the prologue method gives the .stack_sizes frame of {len(agree)} of the "
          f"{len(sizes)} Rust functions of {args.stack_sizes_elf}")
    method_problems = [f"prologue {info[a]['frame']} bytes, .stack_sizes {sizes[a]}: {info[a]['name']}"
                       for a in differ]

    # The bound of the analysed ELF: .stack_sizes where it has them, else the prologue method.
    if args.elf != args.stack_sizes_elf:
        data = open(args.elf, "rb").read()
        sections, funcs = elf_sections(data)
        sizes = stack_sizes(data, sections)
        info = disassemble(args.elf, funcs)
        sizes = {a: v for a, v in sizes.items() if a in info}
    by_type = resolve_by_type(args.llvm_ir, info, elf_sections.names) if args.llvm_ir else {}
    worst, by_name, cycles = analyse(info, sizes, by_type, args.drop_type)

    def named(name):
        if name not in by_name:
            raise SystemExit(f"stack_bound: no function {name} in {args.elf}")
        return by_name[name]

    # The harness's own calls inside the measured window: every callee of the case functions
    # (those that call fw_case_begin_at) that is not an entry point's root, another case function
    # (a group of cases, called between cases) nor outside the window; and fw_case_end up to
    # the measurement (its frame and fw_stack_used).
    begin = named("fw_case_begin_at")
    case_fns = [a for a, f in info.items() if begin in f["callees"]]
    entries = list(read_bounds(args.entries))
    roots_of = {}
    for e in entries:
        for pattern, roots in GROUP_ROOTS:
            m = pattern.match(e)
            if m:
                roots_of[e] = roots if roots is not None else [m.group(1)]
                break
        else:
            raise SystemExit(f"stack_bound: no roots for entry point {e!r} (GROUP_ROOTS)")
    all_roots = {named(r) for rs in roots_of.values() for r in rs}
    harness = sorted({c for a in case_fns for c in info[a]["callees"]
                      if c not in all_roots and c not in case_fns and info[c]["name"] not in OUTSIDE_WINDOW})
    end = named("fw_case_end")
    used = worst(named("fw_stack_used"))
    end_own = sizes.get(end, info[end]["frame"])
    h_best = (end_own + used[0] if used[0] is not None else None, [end] + used[1], used[2])
    for c in harness:
        w = worst(c)
        if w[2] and not h_best[2]:
            h_best = w
        elif w[0] is not None and h_best[0] is not None and w[0] > h_best[0]:
            h_best = w

    ceilings = read_bounds(args.bounds) if args.bounds else {}
    marks = measured(args.run) if args.run else {}
    problems, unknowns = list(method_problems), []
    print("| entry point | static bound (bytes) | measured | ceiling | deepest path |")
    print("|---|---:|---:|---:|---|")
    for e in entries:
        results = [worst(named(r)) for r in roots_of[e]] + [h_best]
        unknown = [r[2] for r in results if r[2]]
        top = max((r for r in results if r[0] is not None), key=lambda r: r[0], default=(None, [], None))
        bound = None if unknown else top[0]
        names = [info[a]["name"] for a in top[1]]
        path = " > ".join(names) if args.paths or len(names) <= 6 else \
            " > ".join(names[:3] + [f"... {len(names) - 5} more ..."] + names[-2:])
        mark = marks.get(e)
        ceiling = ceilings.get(e)
        shown = "-" if e not in ceilings else ceiling if ceiling is not None else "UNKNOWN"
        print(f"| {e} | {bound if bound is not None else 'UNKNOWN'} | {mark if mark is not None else '-'} | "
              f"{shown} | {path if bound is not None else unknown[0]} |")
        if args.bounds and e not in ceilings:
            problems.append(f"{e}: not in {args.bounds}")
        elif bound is None:
            # an entry point the analysis cannot bound yet must say so in the ceilings file
            if args.bounds and ceiling is not None:
                problems.append(f"{e}: UNKNOWN ({unknown[0]}), its ceiling is {ceiling}")
            unknowns.append(e)
            continue
        elif args.bounds and ceiling is None:
            print(f"note: {e} has a bound now ({bound}); its ceiling in {args.bounds} can be a number")
        elif ceiling is not None and bound > ceiling:
            problems.append(f"{e}: static bound {bound} above its ceiling {ceiling}")
        if args.run and mark is None:
            problems.append(f"{e}: not in the run {args.run}")
        elif mark is not None and (mark < 0 or mark > bound):
            problems.append(f"{e}: measured {mark} bytes above the static bound {bound}: the analysis is wrong")
    if args.indirect:
        seen, todo = set(), [named(r) for rs in roots_of.values() for r in rs] + harness + [named("fw_stack_used")]
        while todo:
            a = todo.pop()
            if a not in seen:
                seen.add(a)
                todo.extend(info[a]["callees"])
        for a in sorted(seen, key=lambda a: info[a]["name"]):
            for site in info[a]["indirect"]:
                print(f"indirect: {info[a]['name']}: {site}")
    if args.indirect:
        for a in sorted(by_type, key=lambda a: info[a]["name"]):
            targets, cands, why = by_type[a]
            print(f"by type: {info[a]['name']}: {why}: "
                  + ", ".join(sorted(info[t]["name"] for t in targets if t in info)))
    for c in sorted(set(cycles)):
        print(f"recursion (unbounded, on no bounded entry point's path): {c}")
    for part, (depth, why) in BOUNDED_RECURSION.items():
        print(f"bounded recursion: {part}, at most {depth} activations: {why}")
    for caller, (callee, why) in BOUNDED_CYCLES.items():
        print(f"bounded recursion: {callee} > {caller} > {callee}, once: {why}")
    for p in problems:
        print(f"problem: {p}")
    print(f"stack_bound: {len(entries) - len(unknowns)} entry points bounded, {len(unknowns)} UNKNOWN, "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
