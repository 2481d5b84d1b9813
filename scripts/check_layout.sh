#!/usr/bin/env bash
# The layout invariants of ARCHITECTURE.md: no import cycles inside a crate (between files, and
# between top-level modules as ../shared/tools/layer_cycles.py counts them), no source file over
# 350 lines, no #[path] test files, and in `estimator` only the command-line layer (cli/, batch/,
# main.rs, lib.rs) names the CLI's types. Prints what breaks them; exit code 1 if anything does.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
status=0
long=$(find shared generator estimator reproduce testkit python -name '*.rs' -not -path '*/target/*' \
    -exec awk 'END { if (NR > 350) print FILENAME ": " NR " lines" }' {} \;)
if [ -n "$long" ]; then echo "$long"; status=1; fi
paths=$(grep -rln '#\[path' --include='*.rs' shared generator estimator reproduce testkit python || true)
if [ -n "$paths" ]; then echo "#[path] in: $paths"; status=1; fi
# Import cycles: the graph of `crate::` and sibling `super::` paths outside tests, per crate.
python3 - <<'PY' || status=1
import os, re, sys
def module_of(src, path):
    rel = os.path.relpath(path, src)[:-3].split(os.sep)
    if rel[-1] in ("mod", "lib", "main"):
        rel = rel[:-1]
    return "::".join(rel) or "crate"
bad = 0
def on_cycles(g, label):
    """Prints each module of graph g that reaches itself (it lies on a cycle); their count."""
    found = 0
    for start in sorted(g):
        seen, todo = set(), list(g[start])
        while todo:
            v = todo.pop()
            if v == start:
                print(f"{label}{start} is on an import cycle")
                found += 1
                break
            if v not in seen:
                seen.add(v)
                todo.extend(g[v])
    return found
for crate in ["shared", "generator", "estimator", "reproduce", "testkit", "python"]:
    src = os.path.join(crate, "src")
    files = [os.path.join(d, f) for d, _, fs in os.walk(src) for f in fs if f.endswith(".rs")]
    mods = {module_of(src, f): f for f in files}
    g = {m: set() for m in mods}
    for m, f in mods.items():
        text = open(f, encoding="utf-8").read()
        text = text[: text.find("#[cfg(test)]")] if "#[cfg(test)]" in text else text
        for hit in re.findall(r"crate::([A-Za-z_][A-Za-z0-9_]*(?:::[A-Za-z_][A-Za-z0-9_]*)*)", text):
            parts = hit.split("::")
            for n in range(len(parts), 0, -1):
                cand = "::".join(parts[:n])
                if cand in mods:
                    if cand != m and not m.startswith(cand + "::") and not cand.startswith(m + "::"):
                        g[m].add(cand)
                    break
        if "::" in m:
            parent = m.rsplit("::", 1)[0]
            for hit in re.findall(r"super::([A-Za-z_][A-Za-z0-9_]*)", text):
                cand = parent + "::" + hit
                if cand in mods and cand != m:
                    g[m].add(cand)
    bad += on_cycles(g, f"{crate}: ")
# Between top-level modules (every file under src/a/ counts as module a), counting `use
# crate::{a, b}` groups and `super::` paths that climb to the crate root: no cycle either.
def heads(group):
    out, depth, cur = [], 0, ""
    for ch in group:
        depth += {"{": 1, "}": -1}.get(ch, 0)
        if depth == 0 and ch == ",":
            out.append(cur); cur = ""
        else:
            cur += ch
    out.append(cur)
    return [re.split(r"[:\s{]", x.strip())[0] for x in out if x.strip()]
def targets(text, pattern):
    found = set()
    for m in re.finditer(pattern, text):
        if m.group(1):
            j, depth = m.end(), 1
            while j < len(text) and depth:
                depth += {"{": 1, "}": -1}.get(text[j], 0); j += 1
            found.update(heads(text[m.end():j - 1]))
        else:
            n = re.match(r"[A-Za-z_][A-Za-z0-9_]*", text[m.end():])
            if n: found.add(n.group(0))
    return found
for crate in ["shared", "generator", "estimator", "reproduce", "testkit", "python"]:
    src = os.path.join(crate, "src")
    files = [os.path.join(d, f) for d, _, fs in os.walk(src) for f in fs if f.endswith(".rs")]
    def top(f):
        rel = os.path.relpath(f, src)[:-3].split(os.sep)
        return None if rel in (["lib"], ["main"]) else rel[0]
    tops = {top(f) for f in files} - {None}
    g = {t: set() for t in tops}
    for f in files:
        t = top(f)
        if t is None:
            continue
        rel = os.path.relpath(f, src)[:-3].split(os.sep)
        depth = len(rel) - 1 if rel[-1] == "mod" else len(rel)
        text = open(f, encoding="utf-8").read()
        text = text[: text.find("#[cfg(test)]")] if "#[cfg(test)]" in text else text
        text = re.sub(r"//[^\n]*", "", text)
        found = targets(text, r"crate::(\{)?")
        for m in re.finditer(r"((?:super::)+)", text):
            if m.group(1).count("super::") >= depth:
                found |= targets(text[m.start():], r"^(?:super::)+(\{)?")
        g[t] |= {x for x in found if x in tops and x != t}
    bad += on_cycles(g, f"{crate}: top-level module ")
# Below the command line, no module names the CLI's types.
cli_layer = ("cli", "batch", "main", "lib")
src = os.path.join("estimator", "src")
for d, _, fs in os.walk(src):
    for f in fs:
        if not f.endswith(".rs"):
            continue
        path = os.path.join(d, f)
        top = os.path.relpath(path, src).split(os.sep)[0].removesuffix(".rs")
        if top in cli_layer:
            continue
        text = open(path, encoding="utf-8").read()
        text = text[: text.find("#[cfg(test)]")] if "#[cfg(test)]" in text else text
        code = "\n".join(l for l in text.splitlines() if not l.lstrip().startswith("//"))
        if re.search(r"crate::cli\b|crate::EstimateArgs\b|\bEstimateArgs\b|\bModelArgs\b", code):
            print(f"estimator: {path} names the CLI's types below the command line")
            bad += 1
sys.exit(1 if bad else 0)
PY
[ "$status" = 0 ] && echo "layout: ok (no cycles between files or top-level modules, no file over 350 lines, no #[path], the CLI's types only in its layer)"
exit "$status"
