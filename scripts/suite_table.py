"""The end every rendered suite's table shares (`falls_suite.py`, `swings_suite.py`): the line
naming the script and its time, the table printed, and written to `--md` where given."""
import time


def finish(lines, script, started, md):
    """Appends the made-by line to `lines` (markdown), prints them, writes them to `md`."""
    lines = lines + ["", f"Made by `scripts/{script}` in {time.time() - started:.0f} s."]
    text = "\n".join(lines) + "\n"
    if md:
        with open(md, "w") as f:
            f.write(text)
    print(text)
