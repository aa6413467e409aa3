"""Every public function and method has a docstring with an example, and the examples run;
the type stubs (_chasles.pyi) name every function, class and parameter the module has;
`import chasles` does not import scipy."""

import ast
import doctest
import inspect
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import chasles
import chasles._chasles as native

STUB = pathlib.Path(chasles.__file__).with_name("_chasles.pyi")


def documented():
    """(name, object) of every public function, class and method."""
    for name in chasles.__all__:
        obj = getattr(chasles, name)
        yield name, obj
        if inspect.isclass(obj):
            for m, member in vars(obj).items():
                if not m.startswith("_"):
                    yield f"{name}.{m}", getattr(obj, m)


@pytest.mark.parametrize("name,obj", list(documented()), ids=lambda x: x if isinstance(x, str) else "")
def test_the_docstring_has_an_example_that_runs(name, obj):
    doc = inspect.getdoc(obj) or ""
    if name.startswith(("Pose.", "Rig.")) and not callable(obj):
        assert doc, f"{name} has no docstring"
        return
    assert ">>>" in doc, f"{name} has no example"
    test = doctest.DocTestParser().get_doctest(doc, {"np": np}, name, None, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples failed"


def stub_functions():
    tree = ast.parse(STUB.read_text())
    funcs, classes = {}, {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            funcs[node.name] = node
        elif isinstance(node, ast.ClassDef):
            classes[node.name] = {n.name: n for n in node.body if isinstance(n, ast.FunctionDef)}
    return funcs, classes


def params(node):
    a = node.args
    names = [x.arg for x in a.posonlyargs + a.args if x.arg not in ("self", "cls")]
    return names, [x.arg for x in a.kwonlyargs]


def test_the_stubs_match_the_module():
    funcs, classes = stub_functions()
    public = {n for n in dir(native) if not n.startswith("_")}
    native_funcs = {n for n in public if inspect.isbuiltin(getattr(native, n))}
    assert native_funcs == set(funcs), native_funcs ^ set(funcs)
    assert {n for n in public if inspect.isclass(getattr(native, n))} == set(classes)
    for name, node in funcs.items():
        sig = inspect.signature(getattr(native, name))
        positional = [p.name for p in sig.parameters.values() if p.kind != p.KEYWORD_ONLY]
        keyword = [p.name for p in sig.parameters.values() if p.kind == p.KEYWORD_ONLY]
        assert params(node) == (positional, keyword), name
    for cls, methods in classes.items():
        for m in methods:
            if m.startswith("__") and m != "__init__":
                continue
            assert hasattr(getattr(native, cls), m), f"{cls}.{m}"
        for m, member in vars(getattr(native, cls)).items():
            if not m.startswith("_"):
                assert m in methods, f"{cls}.{m} is not in the stubs"


def test_the_package_is_typed():
    assert STUB.with_name("py.typed").exists()


def test_importing_chasles_does_not_import_scipy():
    code = "import sys, chasles; chasles.quat_mul([1,0,0,0],[1,0,0,0]); print('scipy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
