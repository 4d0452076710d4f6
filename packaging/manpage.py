#!/usr/bin/env python3
"""The manual page nlsubdiv(1), written from the command's own --help texts.

    packaging/manpage.py BIN OUTPUT      e.g. target/release/nlsubdiv nlsubdiv.1

The page is generated rather than kept by hand so that it cannot drift from the command:
every subcommand that `BIN --help` lists gets a section made from `BIN SUBCOMMAND --help`
(usage, arguments, options with their defaults and possible values, notes, examples), and the
exit statuses come from the top-level help. The parser reads clap's two help layouts: short
(`  -q, --quiet   text` on one line) and long (the text indented on the following lines).
"""

import re
import subprocess
import sys

HEADING = re.compile(r"^([A-Z][A-Za-z ]*):$")
USAGE = re.compile(r"^Usage: (.*)$")


def run_help(binary, *args):
    out = subprocess.run([binary, *args, "--help"], check=True, capture_output=True, text=True)
    return out.stdout.rstrip("\n").split("\n")


def escape(text):
    """Plain text to roff: backslashes, option dashes, quotes from backticks, non-ASCII."""
    text = text.replace("\\", "\\e")
    text = re.sub(r"(?<![\w-])-(?=[-\w])", r"\\-", text)
    text = re.sub(r"(?<=\\-)-", r"\\-", text)
    text = re.sub(r"`([^`]*)`", r"\\(oq\1\\(cq", text)
    text = "".join(c if ord(c) < 128 else "\\[u%04X]" % ord(c) for c in text)
    return text


def roff_line(text):
    """One output line of running text (a leading dot or quote would be a request)."""
    line = escape(text)
    return "\\&" + line if line[:1] in (".", "'") else line


def term_roff(term):
    """An option or argument term: options bold, placeholders italic."""
    parts = []
    for token in re.split(r"(\s+|,)", term):
        if token.startswith("-"):
            parts.append("\\fB" + escape(token) + "\\fR")
        elif token.startswith("<") and token.endswith(">"):
            parts.append("\\fI" + escape(token[1:-1]) + "\\fR")
        else:
            parts.append(escape(token))
    return "".join(parts)


def parse(lines):
    """A help text as (about, usage, [(heading, [(term, [paragraph...])])], [paragraph...]).

    Paragraphs are lists of lines; a description paragraph of a long-help item may be a list
    ("Possible values:" then "- name: text" lines), written one line per value.
    """
    about, usage, sections, notes = [], None, [], []
    i, n = 0, len(lines)
    while i < n and lines[i].strip():
        about.append(lines[i].strip())
        i += 1
    current = None  # the list section being read
    paragraph = []

    def flush_note():
        if paragraph:
            notes.append(list(paragraph))
            paragraph.clear()

    while i < n:
        line = lines[i]
        m_usage, m_head = USAGE.match(line), HEADING.match(line)
        if m_usage:
            flush_note()
            usage, current = m_usage.group(1), None
        elif m_head:
            flush_note()
            current = (m_head.group(1), [])
            sections.append(current)
        elif current is not None and line.startswith("  ") and line.strip():
            indent = len(line) - len(line.lstrip(" "))
            body = line.strip()
            items = current[1]
            if indent == 2 or (indent <= 6 and re.match(r"-[^ ]", body)) or not items:
                # A new item: "term  description" (short help) or "term" alone (long help).
                split = re.split(r"\s{2,}", body, maxsplit=1)
                items.append([split[0], [split[1:]]])
            else:
                items[-1][1][-1].append(body)
        elif not line.strip():
            if current is not None and current[1] and current[1][-1][1][-1]:
                current[1][-1][1].append([])  # a paragraph break inside a long-help item
            flush_note()
        else:
            current = None
            paragraph.append(line.strip())
        i += 1
    flush_note()
    for _, items in sections:
        for item in items:
            item[1] = [p for p in item[1] if p]
    return about, usage, sections, notes


def write_items(out, items):
    for term, paras in items:
        out.append(".TP")
        out.append(term_roff(term))
        for k, para in enumerate(paras):
            if k:
                out.append(".IP")
            values = [line for line in para if line.startswith("- ")]
            for line in para:
                if not line.startswith("- "):
                    out.append(roff_line(line))
            if values:  # "Possible values:" then "- name: text": a nested list
                out.append(".RS")
                for line in values:
                    name, _, text = line[2:].partition(":")
                    out.append(".TP")
                    out.append("\\fB" + escape(name) + "\\fR")
                    out.append(roff_line(text.strip()))
                out.append(".RE")


def write_usage(out, usage):
    words = usage.split(" ", 1)
    out.append(".B " + escape(words[0]))
    if len(words) > 1:
        out.append(term_roff(words[1]))
    out.append(".br")


def write_notes(out, notes):
    for para in notes:
        out.append(".PP")
        for line in para:
            out.append(roff_line(line))


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: manpage.py BIN OUTPUT")
    binary, output = sys.argv[1], sys.argv[2]
    version = subprocess.run([binary, "--version"], check=True, capture_output=True, text=True).stdout.split()[-1]
    about, usage, sections, notes = parse(run_help(binary))
    commands = [t for h, items in sections if h == "Commands" for t, _ in items if t != "help"]
    if not commands:
        sys.exit("manpage.py: `%s --help` lists no commands" % binary)
    subs = {c: parse(run_help(binary, c)) for c in commands}

    out = ['.TH NLSUBDIV 1 "" "nlsubdiv %s" "User Commands"' % version, ".SH NAME"]
    summary = about[0].split(": ")[0]  # the whatis line: the part before a colon
    out.append("nlsubdiv \\- " + escape(summary[0].lower() + summary[1:]))
    out.append(".SH SYNOPSIS")
    for c in commands:
        if subs[c][1]:
            write_usage(out, subs[c][1])
    out.append(".SH DESCRIPTION")
    for line in about:
        out.append(roff_line(line))
    write_notes(out, notes)
    out.append(".PP")
    out.append("The commands:")
    for h, items in sections:
        if h == "Commands":
            write_items(out, [i for i in items if i[0] != "help"])
    for h, items in sections:
        if h not in ("Commands", "Exit status"):
            out.append(".SH " + escape(h.upper()))
            write_items(out, items)
    out.append(".SH COMMANDS")
    for c in commands:
        s_about, s_usage, s_sections, s_notes = subs[c]
        out.append('.SS "nlsubdiv %s"' % escape(c))
        for line in s_about:
            out.append(roff_line(line))
        if s_usage:
            out.append(".PP")
            write_usage(out, s_usage)
        for h, items in s_sections:
            out.append(".PP")
            out.append("\\fI%s:\\fR" % escape(h))
            write_items(out, items)
        write_notes(out, s_notes)
    for h, items in sections:
        if h == "Exit status":
            out.append(".SH EXIT STATUS")
            write_items(out, items)
    out.append(".SH SEE ALSO")
    out.append("The C library behind the command: the header")
    out.append(".I nlsubdiv.h")
    out.append("and")
    out.append(".BR pkg-config (1)")
    out.append("module")
    out.append(".B nlsubdiv")
    out.append("(Debian package libnlsubdiv\\-dev).")
    with open(output, "w", encoding="ascii") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
