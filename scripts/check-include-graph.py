#!/usr/bin/env python3
"""The include graph of MRGI's GPU layer, class by class, and its cycles.

Each class of the layer (a vtkMRGI*.h under the given folders) is a node;
X -> Y when X.h or X.cxx includes "Y.h" (generated shader headers and VTK's
own are not nodes). Prints the graph (or Graphviz with --dot) and exits 1
when a cycle exists, naming it. --self-test checks that a made-up cycle is
found and a made-up DAG is not.

Usage: check-include-graph.py [--dot] [FOLDER ...]   (default: Rendering)
"""
import os
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s+"(vtkMRGI\w+)\.h"', re.M)


def graph(folders):
    files = {}
    for folder in folders:
        for root, _, names in os.walk(folder):
            for name in names:
                stem, ext = os.path.splitext(name)
                if stem.startswith("vtkMRGI") and ext in (".h", ".cxx"):
                    files.setdefault(stem, []).append(os.path.join(root, name))
    nodes = {stem for stem, paths in files.items() if any(p.endswith(".h") for p in paths)}
    edges = {n: set() for n in nodes}
    for stem, paths in files.items():
        if stem not in nodes:
            continue
        for path in paths:
            with open(path, encoding="utf-8") as f:
                for target in INCLUDE.findall(f.read()):
                    if target in nodes and target != stem:
                        edges[stem].add(target)
    return edges


def cycles(edges):
    """Every elementary cycle found by depth-first search (one per back edge)."""
    found, state, stack = [], {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(edges[n]):
            if state.get(m) == 1:
                found.append(stack[stack.index(m):] + [m])
            elif m not in state:
                visit(m)
        stack.pop()
        state[n] = 2

    for n in sorted(edges):
        if n not in state:
            visit(n)
    return found


def self_test():
    with tempfile.TemporaryDirectory() as d:
        def write(name, includes):
            with open(os.path.join(d, name), "w") as f:
                f.write("".join('#include "%s.h"\n' % i for i in includes))
        write("vtkMRGIA.h", ["vtkMRGIB"])
        write("vtkMRGIB.h", [])
        write("vtkMRGIB.cxx", ["vtkMRGIB", "vtkMRGIC", "vtkMRGIGeneratedFS"])
        write("vtkMRGIC.h", [])
        assert not cycles(graph([d])), "a DAG reported as cyclic"
        write("vtkMRGIC.cxx", ["vtkMRGIA"])
        found = cycles(graph([d]))
        assert found and set(found[0]) == {"vtkMRGIA", "vtkMRGIB", "vtkMRGIC"}, found
    print("self-test: a three-class cycle is found, the DAG passes")
    return 0


def main(argv):
    if "--self-test" in argv:
        return self_test()
    dot = "--dot" in argv
    folders = [a for a in argv if not a.startswith("--")] or ["Rendering"]
    edges = graph(folders)
    if dot:
        print("digraph mrgi {")
        for n in sorted(edges):
            for m in sorted(edges[n]):
                print('  "%s" -> "%s";' % (n, m))
        print("}")
    else:
        for n in sorted(edges):
            print("%s -> %s" % (n, ", ".join(sorted(edges[n])) or "(nothing)"))
    found = cycles(edges)
    for c in found:
        print("CYCLE: " + " -> ".join(c), file=sys.stderr)
    print("%d classes, %d include edges, %d cycles" %
          (len(edges), sum(len(v) for v in edges.values()), len(found)), file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
