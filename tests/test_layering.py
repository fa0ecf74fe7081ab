"""The two layers (docs/DESIGN.md, "Layers"), checked on the tree itself.

- The physics trees (``boat_dynamics/physics``, ``ocean_sim/physics``) never import rclpy,
  rosbags, the ROS message packages or the ROS side of boatsim, at module level or inside
  functions (read from the source, so a function-level import is caught without running it).
- Importing every physics module loads none of them (run in a fresh interpreter).
- Topic names and QoS profiles are spelled only in ``boat_msgs_py``.
"""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PHYSICS = [SRC / "boat_dynamics" / "physics", SRC / "ocean_sim" / "physics"]
#: Top-level packages the physics core must not import.
FORBIDDEN = {"rclpy", "rosbags", "boat_msgs", "boat_msgs_py", "rpyutils", "rosidl_runtime_py",
             "std_msgs", "geometry_msgs", "nav_msgs", "sensor_msgs", "diagnostic_msgs",
             "rosgraph_msgs", "builtin_interfaces", "rcl_interfaces", "matplotlib"}
#: The ROS and tool layers of boatsim itself.
FORBIDDEN_PREFIXES = ("boat_dynamics.ros", "boat_dynamics.tools", "boat_dynamics.cli",
                      "ocean_sim.ros")


def _modules(root: Path) -> list[str]:
    """Every module and package under ``root`` (a package by its __init__.py)."""
    names = set()
    for p in root.rglob("*.py"):
        parts = p.relative_to(SRC).with_suffix("").parts
        names.add(".".join(parts[:-1] if p.name == "__init__.py" else parts))
    return sorted(names)


def imported_names(source: str) -> list[tuple[int, str]]:
    """(line, module) of every import in ``source``, wherever it stands, and of every
    ``importlib.import_module("...")`` / ``__import__("...")`` with a literal name."""
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            out.append((node.lineno, node.module))
        elif (isinstance(node, ast.Call) and node.args
              and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)
              and ((isinstance(node.func, ast.Name) and node.func.id == "__import__")
                   or (isinstance(node.func, ast.Attribute)
                       and node.func.attr == "import_module"))):
            out.append((node.lineno, node.args[0].value))
    return out


def _violations(source: str) -> list[str]:
    return [f"line {line}: {name}" for line, name in imported_names(source)
            if name.split(".")[0] in FORBIDDEN
            or any(name == p or name.startswith(p + ".") for p in FORBIDDEN_PREFIXES)]


def test_the_scan_sees_imports_inside_functions():
    source = ("import numpy\n"
              "def f():\n"
              "    from rclpy.node import Node\n"
              "    import importlib\n"
              "    importlib.import_module('rosbags.rosbag2')\n"
              "    class A:\n"
              "        def g(self):\n"
              "            import boat_dynamics.ros.node\n")
    assert _violations(source) == ["line 3: rclpy.node", "line 5: rosbags.rosbag2",
                                   "line 8: boat_dynamics.ros.node"]


@pytest.mark.parametrize("root", PHYSICS, ids=lambda p: str(p.relative_to(SRC)))
def test_physics_tree_imports_no_ros_anywhere(root):
    files = sorted(root.rglob("*.py"))
    assert len(files) >= 4
    bad = {str(f.relative_to(SRC)): v for f in files
           if (v := _violations(f.read_text(encoding="utf-8")))}
    assert bad == {}


def test_importing_the_physics_core_loads_no_ros():
    modules = [m for root in PHYSICS for m in _modules(root)]
    assert {"boat_dynamics.physics.scenario", "boat_dynamics.physics.scenario.boat",
            "ocean_sim.physics.waves"} <= set(modules)
    code = (
        "import sys\n"
        f"for m in {modules!r}: __import__(m)\n"
        f"bad = sorted(m for m in sys.modules if m.split('.')[0] in {sorted(FORBIDDEN)!r})\n"
        "print(','.join(bad))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == ""


def test_the_gymnasium_environments_import_no_ros():
    """boat_dynamics.gym is an adapter over the physics core for learning loops: no ROS."""
    assert _violations((SRC / "boat_dynamics" / "gym.py").read_text(encoding="utf-8")) == []
    code = ("import sys, boat_dynamics.gym\n"
            f"print(','.join(sorted(m for m in sys.modules if m.split('.')[0] in "
            f"{sorted(FORBIDDEN)!r})))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == ""


def test_boat_dynamics_has_only_the_layers_at_its_top():
    top = sorted(p.name for p in (SRC / "boat_dynamics").iterdir()
                 if p.name != "__pycache__")
    # bags.py: the deprecated alias of tools/bags.py (CHANGES.md, "Changes to the contract");
    # data: package data (coefficient files), no code
    # gym.py: Gymnasium environments, an adapter over the physics core without ROS (below)
    # gym_ros.py: the same task over a running simulation (ROS lockstep)
    assert top == ["__init__.py", "__main__.py", "bags.py", "cli.py", "data", "gym.py",
                   "gym_ros.py", "physics", "ros", "tools"]
    assert not list((SRC / "boat_dynamics" / "data").rglob("*.py"))


def test_the_old_compare_bags_import_still_works_and_says_where_it_went():
    code = ("import warnings\n"
            "with warnings.catch_warnings(record=True) as w:\n"
            "    warnings.simplefilter('always')\n"
            "    from boat_dynamics.bags import compare_bags\n"
            "from boat_dynamics.tools.bags import compare_bags as new\n"
            "assert compare_bags is new\n"
            "print([str(x.message) for x in w if x.category is DeprecationWarning])\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert "import boat_dynamics.tools.bags" in out.stdout


#: Topic names of the contract (any string literal containing one outside boat_msgs_py is a
#: second spelling).
TOPIC_FRAGMENTS = ("/ocean/", "cmd_thrust", "cmd_rudder", "/clock", "/diagnostics",
                   "/boatsim/", "/rosout", "/parameter_events", "wrench/")


def _literals(tree: ast.AST) -> list[tuple[int, str]]:
    """(line, text) of string literals that are not docstrings."""
    docstrings = {id(n.body[0].value) for n in ast.walk(tree)
                  if isinstance(n, ast.Module | ast.ClassDef | ast.FunctionDef)
                  and n.body and isinstance(n.body[0], ast.Expr)
                  and isinstance(n.body[0].value, ast.Constant)}
    return [(n.lineno, n.value) for n in ast.walk(tree)
            if isinstance(n, ast.Constant) and isinstance(n.value, str)
            and id(n) not in docstrings]


def _is_message(text: str) -> bool:
    """Text meant for people (a log line, an error, a help string): it has spaces."""
    return " " in text.strip()


def test_topic_names_and_qos_only_in_boat_msgs_py():
    found = []
    for f in sorted(SRC.rglob("*.py")):
        if "boat_msgs_py" in f.parts:
            continue
        tree = ast.parse(f.read_text(encoding="utf-8"))
        where = str(f.relative_to(SRC))
        found += [f"{where}:{line}: {text!r}" for line, text in _literals(tree)
                  if not _is_message(text) and any(t in text for t in TOPIC_FRAGMENTS)]
        found += [f"{where}:{n.lineno}: QoSProfile(...)" for n in ast.walk(tree)
                  if isinstance(n, ast.Call) and getattr(n.func, "id", None) == "QoSProfile"]
    assert found == []


def test_the_contract_package_sits_between_the_layers():
    # boat_msgs_py converts core objects to messages: it may read the physics layers, never
    # the ROS nodes or tools that use it (no package cycle through the adapters).
    bad = {}
    for f in sorted((SRC / "boat_msgs_py").rglob("*.py")):
        names = [n for _, n in imported_names(f.read_text(encoding="utf-8"))
                 if n.split(".")[0] in ("ocean_sim", "boat_dynamics")
                 and not n.startswith(("ocean_sim.physics", "boat_dynamics.physics"))]
        if names:
            bad[f.name] = names
    assert bad == {}


def test_ocean_sim_never_imports_boat_dynamics():
    # the sea is the lower layer: the boats read it, it knows nothing of them
    bad = {str(f.relative_to(SRC)): names for f in sorted((SRC / "ocean_sim").rglob("*.py"))
           if (names := [n for _, n in imported_names(f.read_text(encoding="utf-8"))
                         if n.split(".")[0] == "boat_dynamics"])}
    assert bad == {}


def _module_of(path: Path) -> str:
    parts = path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if path.name == "__init__.py" else parts)


def test_the_physics_modules_import_each_other_in_no_circle():
    # before the folders by role: hull_drag <-> mesh_buoyancy, through the clip that lived in
    # mesh_buoyancy; the clip is a module of its own (body/clip.py)
    files = sorted((SRC / "boat_dynamics" / "physics").rglob("*.py"))
    known = {_module_of(f) for f in files}
    edges = {}
    for f in files:
        tree = ast.parse(f.read_text(encoding="utf-8"))
        names = {n for _, n in imported_names(f.read_text(encoding="utf-8"))}
        # ``from package import module``: the module, not just its package
        names |= {f"{n.module}.{a.name}" for n in ast.walk(tree)
                  if isinstance(n, ast.ImportFrom) and n.level == 0 and n.module
                  for a in n.names}
        edges[_module_of(f)] = {n for n in names if n in known and n != _module_of(f)
                                and not _module_of(f).startswith(n + ".")}
    state, circle = {}, []

    def visit(m: str, path: list[str]) -> None:
        state[m] = "open"
        for n in sorted(edges.get(m, ())):
            if state.get(n) == "open":
                circle.append(path[path.index(n):] + [n] if n in path else [m, n])
            elif n not in state:
                visit(n, [*path, n])
        state[m] = "done"

    for m in sorted(edges):
        if m not in state:
            visit(m, [m])
    assert circle == []


def test_the_old_physics_module_names_still_import_and_say_where_they_went():
    code = ("import importlib, warnings\n"
            "from boat_dynamics.physics import MOVED\n"
            "said = []\n"
            "for name, folder in sorted(MOVED.items()):\n"
            "    new = importlib.import_module(f'boat_dynamics.physics.{folder}.{name}')\n"
            "    with warnings.catch_warnings(record=True) as w:\n"
            "        warnings.simplefilter('always')\n"
            "        old = importlib.import_module(f'boat_dynamics.physics.{name}')\n"
            "    assert old is new, name\n"
            "    said += [str(x.message) for x in w if x.category is DeprecationWarning]\n"
            "print(len(MOVED), len(said)); print(said[0])\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    count, warned = out.stdout.splitlines()[0].split()
    assert int(count) == 34 and warned == count, out.stdout
    assert "has moved to boat_dynamics.physics." in out.stdout


def test_no_function_binds_a_standard_stream_at_import():
    """A default ``status=sys.stderr`` is the stream of whoever imported the module first.

    Under pytest that was one test's capture, closed when it ended: a later call printed to
    it and raised ``ValueError: I/O operation on closed file`` (view_bag, once, by test
    order). Streams are looked up when called (``status=None``).
    """
    bound = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                defaults = [*node.args.defaults, *node.args.kw_defaults]
                bound += [f"{path.relative_to(SRC)}:{node.lineno} {node.name}"
                          for d in defaults if d is not None
                          and ast.unparse(d) in ("sys.stderr", "sys.stdout", "sys.stdin")]
    assert not bound, bound
