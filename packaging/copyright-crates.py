#!/usr/bin/env python3
"""The crates part of debian/copyright, from Cargo.lock.

    packaging/copyright-crates.py            print the Files paragraphs of every crate
    packaging/copyright-crates.py --check    exit 1 when debian/copyright's vendor/
                                             paragraphs are not these (a crate added, gone
                                             or of another version)

The binary packages link these crates statically (the library: libm, arrayvec; the
command: clap, png, serde_json, ... as well), and a source package made with a vendor/ folder
(`cargo vendor --locked vendor`, debian/README.source) ships their sources: debian/copyright
names each one's folder there, its copyright holders (the Copyright lines of its licence files,
else the authors in its Cargo.toml) and its licence (its Cargo.toml's SPDX expression in DEP-5
spelling). The crates are vendored into a temporary folder from cargo's registry (offline when
the registry already holds them) so the folders are the ones `cargo vendor` makes.
"""

import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def vendored():
    """[(folder, name, version, license, copyright lines)] for every crate of Cargo.lock."""
    with tempfile.TemporaryDirectory(prefix="nls-vendor-") as tmp:
        vendor = os.path.join(tmp, "vendor")
        cmd = ["cargo", "vendor", "--locked", "--quiet", vendor]
        if subprocess.run(cmd + ["--offline"], cwd=ROOT, capture_output=True).returncode != 0:
            subprocess.run(cmd, cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
        crates = []
        for folder in sorted(os.listdir(vendor)):
            path = os.path.join(vendor, folder)
            meta = json.loads(
                subprocess.run(
                    ["cargo", "read-manifest", "--manifest-path", os.path.join(path, "Cargo.toml")],
                    cwd=ROOT,
                    check=True,
                    capture_output=True,
                    text=True,
                ).stdout
            )
            holders = []
            for name in sorted(os.listdir(path)):
                if not re.match(r"(?i)(license|licence|copying|unlicense|notice)", name):
                    continue
                full = os.path.join(path, name)
                if not os.path.isfile(full):
                    continue
                with open(full, encoding="utf-8", errors="replace") as f:
                    for line in f:
                        m = re.match(r"\s*(?:Copyright\s+(?:\([cC]\)\s*|©\s*)?|\([cC]\)\s+(?=\d))(.*\S)", line)
                        # Not the licence texts' own uses of the word ("Copyright License",
                        # "[yyyy] [name of copyright owner]", "copyright notice", ...).
                        if m and not re.search(r"yyyy|owner|notice|holders?\b|^licen[cs]e\b", m.group(1), re.I):
                            holder = m.group(1)
                            if holder not in holders:
                                holders.append(holder)
            authors = [re.sub(r"\s*<[^>]*>?", "", a) for a in meta.get("authors") or []]
            authors = ", ".join(authors) or "the %s developers" % meta["name"]
            # A line with years only ("Copyright 2017") names the authors of Cargo.toml.
            holders = [h + " " + authors if re.fullmatch(r"[0-9, -]+", h) else h for h in holders]
            holders = holders or [authors]
            crates.append((folder, meta["name"], meta["version"], meta["license"], holders))
        return crates


def dep5_license(spdx):
    return re.sub(r"\bAND\b", "and", re.sub(r"\bOR\b", "or", spdx)).replace("/", " or ")


def paragraphs(crates):
    out = []
    for folder, name, version, lic, holders in crates:
        out.append("Files: vendor/%s/*" % folder)
        out.append("Copyright: " + holders[0])
        out.extend("           " + h for h in holders[1:])
        out.append("License: " + dep5_license(lic))
        out.append("Comment: crate %s %s" % (name, version))
        out.append("")
    return "\n".join(out)


def main():
    crates = vendored()
    text = paragraphs(crates)
    if sys.argv[1:] == ["--check"]:
        with open(os.path.join(ROOT, "debian", "copyright"), encoding="utf-8") as f:
            copyright_text = f.read()
        # The paragraphs about vendor/, in their order, must be the generated ones.
        ours = [p for p in copyright_text.split("\n\n") if p.startswith("Files: vendor/")]
        if "\n\n".join(ours) + "\n" != text:
            print("debian/copyright: its vendor/ paragraphs differ from Cargo.lock's crates; regenerate")
            print("them with packaging/copyright-crates.py (the output replaces them)")
            sys.exit(1)
        print("debian/copyright: the %d crates of Cargo.lock, each with its licence" % len(crates))
    elif sys.argv[1:]:
        sys.exit("usage: copyright-crates.py [--check]")
    else:
        print(text)


if __name__ == "__main__":
    main()
