"""The README's Python blocks run as written (its C, C++ and Rust blocks are run by tests/readme.rs)."""

import pathlib
import re

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def python_blocks(text):
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def test_readme_python_blocks_run():
    blocks = python_blocks(README.read_text())
    assert blocks, "README.md should show Python"
    for code in blocks:
        namespace = {}
        exec(compile(code, str(README), "exec"), namespace)
        # The example's answers: the lifted tetrahedron overlaps the other, the sphere is apart.
        assert len(namespace["pairs"]) > 0
        assert abs(namespace["d"] - 0.9) < 1e-12
        assert namespace["hits"].all()
