#!/usr/bin/env python3
"""The layering of src/ (issue 18): each module may use only modules of its own layer or of
a layer below it, base <- model <- io <- run <- app, and only the deck module knows the
deck's keywords (no model module uses it).

    check_layers.py [ROOT]

Reads the `use` statements of every .f90 file under src/ and app/; prints each violation
and the module graph's size; exit 1 on a violation."""
import os
import re
import sys

ORDER = ["base", "model", "io", "run", "app"]
USE = re.compile(r"^\s*use\s*(?:,\s*\w+\s*)?(?:::)?\s*(\w+)", re.IGNORECASE)


def modules(root):
    """module name -> (layer, path), and path -> the spb_ modules it uses."""
    where, uses = {}, {}
    for layer in ORDER:
        top = os.path.join(root, "app" if layer == "app" else os.path.join("src", layer))
        for d, _, files in os.walk(top):
            for f in sorted(files):
                if not f.endswith(".f90"):
                    continue
                path = os.path.join(d, f)
                text = open(path, encoding="utf-8", errors="replace").read()
                for m in re.finditer(r"^\s*(?:module|program)\s+(\w+)\s*$", text,
                                     re.IGNORECASE | re.MULTILINE):
                    where[m.group(1).lower()] = (layer, path)
                uses[path] = {m.group(1).lower() for line in text.splitlines()
                              for m in [USE.match(line.split("!")[0])] if m and
                              m.group(1).lower().startswith("spb_")}
    return where, uses


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    where, uses = modules(root)
    bad = 0
    stray = [f for d, _, fs in os.walk(os.path.join(root, "src")) for f in fs
             if f.endswith(".f90") and os.path.dirname(os.path.join(d, f)) == os.path.join(root, "src")]
    for f in stray:
        print(f"src/{f}: not in a layer folder (src/base, src/model, src/io, src/run)")
        bad += 1
    edges = 0
    for path, used in sorted(uses.items()):
        layer = next(l for l in ORDER if (os.sep + (l if l == "app" else os.path.join("src", l)) + os.sep) in path)
        for mod in sorted(used):
            edges += 1
            if mod not in where:
                # spb_par: one of two sources of the same module (MPI or serial), both in base
                continue
            ul = where[mod][0]
            if ORDER.index(ul) > ORDER.index(layer):
                print(f"{os.path.relpath(path, root)} ({layer}) uses {mod} ({ul}): a layer above")
                bad += 1
            if layer == "model" and mod.startswith("spb_deck"):
                print(f"{os.path.relpath(path, root)}: a model module uses the deck module")
                bad += 1
    print(f"{len(uses)} files, {edges} uses of spb_ modules, {bad} violations")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
