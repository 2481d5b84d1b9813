"""What every rendered suite shares (`falls_suite.py`, `swings_suite.py`): its arguments (the
estimate binary, a folder for the scenes and runs, `--md`), and its table's end: the line naming
the script and its time, the table printed, and written to `--md` where given."""
import argparse, os, time


def arguments(doc):
    """The suite's arguments (described by its docstring `doc`), its output folder made."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("estimate")
    ap.add_argument("out")
    ap.add_argument("--md", help="write the table here (markdown)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    return a


def finish(lines, script, started, md):
    """Appends the made-by line to `lines` (markdown), prints them, writes them to `md`."""
    lines = lines + ["", f"Made by `scripts/{script}` in {time.time() - started:.0f} s."]
    text = "\n".join(lines) + "\n"
    if md:
        with open(md, "w") as f:
            f.write(text)
    print(text)
