"""Runs a Python block of README.md verbatim, so that the documented API cannot rot.

Used by TestReadmeExample (the first example) and TestReadmeFlight (the flight script).
The block is the first ```python fence after the given heading; it runs in this process
(its variables can be inspected afterwards), with sys.argv = [script] + argv and a
scratch working directory, its stdout captured and echoed.
"""
import contextlib
import io
import os
import re
import sys
import tempfile

README = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "README.md")


def readme_block(heading):
    """The code of the first ```python block after the line `heading` of README.md."""
    text = open(README, encoding="utf-8").read()
    if f"\n{heading}\n" not in text:
        raise AssertionError(f"README.md has no heading {heading!r}")
    section = text.split(f"\n{heading}\n", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


@contextlib.contextmanager
def run_readme_block(heading, argv=()):
    """Runs the block; yields (its variables, what it printed, the scratch folder it ran
    in), the folder removed afterwards."""
    code = readme_block(heading)
    with tempfile.TemporaryDirectory() as tmp:
        script = os.path.join(tmp, "example.py")
        with open(script, "w", encoding="utf-8") as f:
            f.write(code)
        old_argv, cwd = sys.argv, os.getcwd()
        sys.argv, printed = [script, *argv], io.StringIO()
        os.chdir(tmp)
        variables = {"__name__": "__main__", "__file__": script}
        try:
            with contextlib.redirect_stdout(printed):
                exec(compile(code, script, "exec"), variables)
        finally:
            sys.argv = old_argv
            os.chdir(cwd)
        print(printed.getvalue())
        yield variables, printed.getvalue(), tmp
