"""The type stubs say what the package has: every public name, with the real parameters."""

import ast
import inspect
import pathlib

import topomill
from topomill import _topomill

PACKAGE = pathlib.Path(topomill.__file__).parent


def stub(name):
    tree = ast.parse((PACKAGE / name).read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            out[node.name] = node
        elif isinstance(node, ast.AnnAssign):
            out[node.target.id] = node
    return {k: v for k, v in out.items() if not k.startswith("_") or k == "__version__"}


def parameters(node):
    a = node.args
    return [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]


def test_the_package_stub_has_every_public_name_and_parameter():
    declared = stub("__init__.pyi")
    assert set(declared) == set(topomill.__all__) | {"__version__"}
    for name, node in declared.items():
        if isinstance(node, ast.FunctionDef):
            real = inspect.signature(getattr(topomill, name))
            assert parameters(node) == [p for p in real.parameters if p != "settings"], name


def test_the_compiled_module_stub_has_every_name():
    declared = stub("_topomill.pyi")
    public = {n for n in dir(_topomill) if not n.startswith("_")}
    assert set(declared) == public
