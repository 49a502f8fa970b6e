"""The package's modules import in one direction (issue 44): scene -> curve/summary -> simulate ->
views -> results -> fit -> batches, each module only from modules of a lower rank, so there is no
circle; a new module must be given its place here. Read from the sources' own import statements
(every one, inside functions too), as tools/include_graph.cmake reads the C++ includes."""
import ast
import pathlib

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "layerjkr"

# Each module's rank: it may import only modules of a lower rank (_core is the C++ extension).
RANK = {
    "_core": 0,
    "_common": 1, "_fit_statistics": 1, "_html": 1, "_named_array": 1,
    "_scene": 2, "_instrument": 2, "_fit_options": 2, "_batch_tables": 2,
    "_curve": 3, "_summary": 3, "_simulate": 3,
    "_fit_views": 4, "_profile": 4,
    "_fit_result": 5,
    "_fit": 6,
    "_batch": 7,
    "__init__": 8,
}


def imports_of(path):
    """The package modules `path` imports (relative imports: `from . import x`, `from .x import y`)."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module:
                found.add(node.module.split(".")[0])
            else:
                found.update(alias.name for alias in node.names)
    return found


def test_every_module_has_a_rank():
    modules = {p.stem for p in PACKAGE.glob("*.py")}
    assert modules - set(RANK) == set(), "give the new module its rank in RANK"


def test_imports_run_one_way_only():
    wrong = []
    for path in sorted(PACKAGE.glob("*.py")):
        for target in imports_of(path):
            if RANK.get(target, 99) >= RANK[path.stem]:
                wrong.append("%s (rank %d) imports %s (rank %s)" % (path.stem, RANK[path.stem], target, RANK.get(target)))
    assert wrong == []


def test_the_rule_sees_a_circle(tmp_path):
    # The check itself can fail: a module importing one of its own rank or above is caught.
    bad = tmp_path / "_fit_views.py"
    bad.write_text("def f():\n    from ._fit import simulate\n")
    assert "_fit" in imports_of(bad) and RANK["_fit"] >= RANK["_fit_views"]
