"""The module as a user meets it: importable, documented, its stubs next to it and true to it."""
import ast
import pathlib

import clothsim


def stub_tree():
    path = pathlib.Path(clothsim.__file__).with_name("clothsim.pyi")
    assert path.is_file(), f"no type stubs next to the module at {path}"
    return ast.parse(path.read_text())


def public(names):
    return {n for n in names if not n.startswith("_")}


def test_stubs_name_what_the_module_has():
    tree = stub_tree()
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    assert set(classes) == public(dir(clothsim)) - {"annotations"}
    for name, node in classes.items():
        members = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        members |= {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
        have = public(dir(getattr(clothsim, name)))
        if issubclass(getattr(clothsim, name), BaseException):
            have -= public(dir(BaseException))
        assert public(members) == have, name


def test_everything_has_a_docstring():
    assert clothsim.__doc__ and "bit for bit" in clothsim.__doc__
    for name in public(dir(clothsim)):
        cls = getattr(clothsim, name)
        assert cls.__doc__, name
        for member in public(dir(cls)) - public(dir(BaseException)):
            if issubclass(cls, BaseException):  # attributes: described in the class's docstring
                assert f"{member}:" in cls.__doc__, f"{name}.{member}"
            else:
                assert getattr(cls, member).__doc__, f"{name}.{member}"


def test_exception_hierarchy():
    assert issubclass(clothsim.SceneError, ValueError)
    assert issubclass(clothsim.UnstableError, RuntimeError)
    assert issubclass(clothsim.GpuUnavailableError, RuntimeError)
    assert clothsim.SceneError.__module__ == "clothsim"
