"""Replaces one marked section of a markdown file (BENCHMARKS.md), leaving the other sections
(written by other benchmarks) as they are; appends the section when its markers are absent."""
import os


def replace_section(path, begin, end, section):
    old = open(path).read() if os.path.exists(path) else "# Benchmarks\n"
    if begin in old and end in old:
        new = old[:old.index(begin)] + section + old[old.index(end) + len(end):]
    else:
        new = old.rstrip("\n") + "\n\n" + section + "\n"
    open(path, "w").write(new)
