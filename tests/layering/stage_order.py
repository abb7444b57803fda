#!/usr/bin/env python3
"""The stage order of docs/design.md, checked: a folder under src/ includes only the folders
before it in the order CMakeLists.txt builds them (MIRAGE_STAGES, then the faces built on the
library), never one after it, so data flows one way and a back edge fails the test.

Usage: stage_order.py SRC_DIR STAGE [STAGE ...]   (the stages in order, first to last)
       stage_order.py --self-test
Prints one line per back edge (file:line, the include, which stage it reaches back to) and exits
1 when there is any; "stage order: ok (N files)" otherwise.
"""
import os
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s+"([A-Za-z0-9_]+)/[^"]+"')


def back_edges(src, stages):
    """(file, line, include, its stage) for every include of a later stage; and the files read."""
    rank = {s: i for i, s in enumerate(stages)}
    edges, files = [], 0
    unknown = sorted(d for d in os.listdir(src)
                     if os.path.isdir(os.path.join(src, d)) and d not in rank)
    for d in unknown:
        edges.append((os.path.join(src, d), 0, "", f"a folder not in the stage order {stages}"))
    for stage in stages:
        folder = os.path.join(src, stage)
        if not os.path.isdir(folder):
            continue
        for root, _, names in os.walk(folder):
            for name in sorted(names):
                if not name.endswith((".h", ".cpp", ".inl")):
                    continue
                path = os.path.join(root, name)
                files += 1
                with open(path, encoding="utf-8") as f:
                    for n, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if m and m.group(1) in rank and rank[m.group(1)] > rank[stage]:
                            edges.append((path, n, line.strip(), m.group(1)))
    return edges, files


def self_test():
    with tempfile.TemporaryDirectory() as d:
        for stage, text in [("core", '#include "core/a.h"\n'), ("render", '#include "core/a.h"\n'),
                            ("film", '#include "render/x.h"\n')]:
            os.makedirs(os.path.join(d, stage))
            with open(os.path.join(d, stage, "a.h"), "w") as f:
                f.write(text)
        edges, files = back_edges(d, ["core", "film", "render"])
        assert files == 3, files
        assert len(edges) == 1 and edges[0][3] == "render" and edges[0][1] == 1, edges
        edges, _ = back_edges(d, ["core", "render", "film"])
        assert edges == [], edges
        edges, _ = back_edges(d, ["core", "render"])
        assert len(edges) == 1 and "not in the stage order" in edges[0][3], edges
    print("self-test: ok")


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    src, stages = sys.argv[1], sys.argv[2:]
    edges, files = back_edges(src, stages)
    for path, n, line, stage in edges:
        where = f"{os.path.relpath(path, src)}:{n}" if n else os.path.relpath(path, src)
        print(f"{where}: {line} reaches back to {stage}" if line else f"{where}: {stage}")
    if edges:
        sys.exit(f"stage order: {len(edges)} back edge(s) in {files} files")
    print(f"stage order: ok ({files} files)")


if __name__ == "__main__":
    main()
