"""api_decls.py INCLUDE: what the installed headers under INCLUDE/textura declare, read
from clang's syntax tree of a program that includes <textura/textura.h>: a line
"D name" for every function and variable with external linkage that they declare
(static and inline ones are not exported), and "H path" for every installed header the
program reads (clang -M)."""
import json
import os
import subprocess
import sys

inc = sys.argv[1]
root = os.path.join(inc, "textura") + os.sep
args = ["clang", "-x", "c", "-std=gnu11", "-fsyntax-only", "-I", inc, "-I/usr/include/OpenEXR", "-"]
src = b"#include <textura/textura.h>\n"
tree = subprocess.run(args[:5] + ["-Xclang", "-ast-dump=json"] + args[5:], input=src,
                      capture_output=True, check=True).stdout
names, here = set(), None
for d in json.loads(tree).get("inner", []):
    loc = d.get("loc", {})
    here = loc.get("file") or (loc.get("expansionLoc") or {}).get("file") or here
    if not here or not here.startswith(root) or d.get("isImplicit"):
        continue
    kind, storage = d.get("kind"), d.get("storageClass")
    if (kind == "FunctionDecl" and storage != "static" and not d.get("inline")) or \
            (kind == "VarDecl" and storage == "extern"):
        names.add(d["name"])
deps = subprocess.run(["clang", "-x", "c", "-M", "-I", inc, "-I/usr/include/OpenEXR", "-"],
                      input=src, capture_output=True, check=True).stdout.decode()
heads = {os.path.normpath(p) for p in deps.replace("\\\n", " ").split()}
heads = {p for p in heads if p.startswith(root)}
for n in sorted(names):
    print("D", n)
for h in sorted(heads):
    print("H", h[len(root):])
