"""The tools a run can measure: ours (built in this repo) and the peers installed here.

Each tool knows how to find its binary, which input format it reads (peers get the input
converted by our format-convert, untimed), the exact command of its fair configuration, and
where its output lands. meshrepair writes the format a user asks for (--out-format of the runner):
one tool entry per format, named `meshrepair.glb`, `meshrepair.stl`, ..., each checked on the file
it wrote. Ours are called with one thread (-j 1) so that -j N of the runner
means N busy cores; peers get OMP_NUM_THREADS=1, gmsh also -nt 1 and fTetWild --max-threads 1.
fTetWild is no Debian package: it runs only when asked for (--peers ftetwild) and found on PATH
(FloatTetwild_bin) or given with --tool-path ftetwild=PATH.
"""
import glob
import os
import shutil
from dataclasses import dataclass, field, replace

TASKS = ("tetrahedralize", "meshrepair", "simplify-in-envelope")
VOLUME, SURFACE = "volume", "surface"
OUT_FORMATS = ("glb", "stl", "obj", "drc")  # what meshrepair can be asked to write
ALL_OUT_FORMATS = ("glb", "stl", "drc")  # --out-format all: the formats a user receives
DEFAULT_OUT_FORMAT = {"meshrepair": "glb"}  # tools without an entry keep their one output
FORMAT_NOTES = {"glb": "; GLB: float32 positions", "stl": "; binary STL: float32 corners, welded by mesh-check",
                "obj": "; OBJ: shortest exact decimal of each double",
                "drc": "; Draco .drc: positions quantized to 16 bits per component (the writer's default)"}


@dataclass
class Tool:
    name: str
    task: str
    ours: bool
    output_kind: str  # VOLUME or SURFACE
    fair_config: str  # for the report
    input_ext: str | None = None  # None: reads the original file; else convert to this
    output_name: str = ""  # file the tool writes in its workdir (its extension is the output format)
    program: str = ""  # executable's name in the build folder or on PATH; default: name
    executable: str | None = None
    unavailable: str = ""  # why the tool cannot run here, if it cannot
    version: str = ""
    build_command: object = field(default=None, repr=False)  # (tool, input, workdir, epsilon) -> argv
    find_output: object = field(default=None, repr=False)  # (workdir) -> path or None
    finish_input: object = field(default=None, repr=False)  # (converted input, workdir) -> path the tool gets
    native_exts: tuple = ()  # input extensions (lower case) the tool reads itself: given the original file

    @property
    def available(self):
        return self.executable is not None and not self.unavailable

    def command(self, input_path, workdir, epsilon):
        return self.build_command(self, input_path, workdir, epsilon)

    def final_input(self, converted, workdir):
        return self.finish_input(converted, workdir) if self.finish_input else converted

    def output(self, workdir):
        return self.find_output(workdir)

    @property
    def out_format(self):
        return os.path.splitext(self.output_name)[1].lstrip(".")

    @property
    def program_name(self):
        return self.program or self.name


def _fixed_output(name):
    def find(workdir):
        path = os.path.join(workdir, name)
        return path if os.path.exists(path) else None
    return find


def _tetgen_output(workdir):
    found = sorted(glob.glob(os.path.join(workdir, "in.1.mesh")))
    return found[0] if found else None


def _strip_off_comments(path, workdir):
    """TetGen 1.5 aborts on '#' comment lines in OFF files (valid OFF; format-convert writes one)."""
    with open(path, "rb") as f:
        lines = f.readlines()
    kept = [ln for ln in lines if not ln.lstrip().startswith(b"#")]
    if len(kept) != len(lines):
        with open(path, "wb") as f:
            f.writelines(kept)
    return path


def _gmsh_geo(path, workdir):
    """gmsh meshes the volume inside the STL only when a .geo defines one (as in BASELINE.md)."""
    geo = os.path.join(workdir, "in.geo")
    with open(geo, "w", encoding="utf-8") as f:
        f.write(f'Merge "{os.path.basename(path)}";\nSurface Loop(1) = {{1}};\nVolume(1) = {{1}};\n')
    return geo


def _ours_tetrahedralize(tool, inp, workdir, eps):
    return [tool.executable, inp, os.path.join(workdir, "out.msh"), "-e", repr(eps),
            "--stats", os.path.join(workdir, "stats.json"), "-j", "1", "-q"]


def _ours_meshrepair(tool, inp, workdir, eps):
    return [tool.executable, inp, os.path.join(workdir, tool.output_name), "--stats",
            os.path.join(workdir, "stats.json"), "-q"]


def _ours_simplify(tool, inp, workdir, eps):
    return [tool.executable, inp, os.path.join(workdir, "out.ply"), "-e", repr(eps),
            "--stats", os.path.join(workdir, "stats.json")]


def _tetgen(tool, inp, workdir, eps):
    return [tool.executable, "-pq1.414gQ", inp]


def _ftetwild(tool, inp, workdir, eps):
    # -o inside the work folder: fTetWild names its side files after it (out.msh__sf.obj,
    # out.msh__tracked_surface.stl, out.msh_.csv), so nothing lands beside the input.
    # -e is its own default (1e-3) unless the run's epsilon differs.
    return [tool.executable, "-i", inp, "-o", os.path.join(workdir, "out.msh"), "-e", repr(eps),
            "--max-threads", "1"]


def _gmsh(tool, inp, workdir, eps):
    return [tool.executable, "-3", "-nt", "1", inp, "-o", os.path.join(workdir, "out.msh"), "-format", "msh41"]


def _admesh(tool, inp, workdir, eps):
    return [tool.executable, f"--write-binary-stl={os.path.join(workdir, 'out.stl')}", inp]


def _meshlab(tool, inp, workdir, eps):
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "meshlab_repair.mlx")
    command = [tool.executable, "-i", inp, "-o", os.path.join(workdir, "out.ply"), "-s", script]
    # meshlabserver needs an OpenGL context even for filters: give it a virtual display.
    xvfb = shutil.which("xvfb-run")
    return ([xvfb, "-a"] + command) if xvfb else command


def _ours(name, output_kind, builder, output, config):
    return Tool(name, name, True, output_kind, config, None, output, build_command=builder,
                find_output=_fixed_output(output))


def with_out_format(tool, fmt):
    """A copy of one of our surface tools that writes out.FMT, named TOOL.FMT (its own results rows)."""
    if fmt not in OUT_FORMATS:
        raise ValueError(f"unknown output format {fmt!r}; known: {', '.join(OUT_FORMATS)}")
    output = f"out.{fmt}"
    config = tool.fair_config.replace(tool.output_name, output) + FORMAT_NOTES.get(fmt, "")
    return replace(tool, name=f"{tool.name}.{fmt}", program=tool.program_name, output_name=output,
                   fair_config=config, find_output=_fixed_output(output))


def all_tools():
    """Every tool the runner knows, keyed by name (binaries not located yet)."""
    tools = [
        _ours("tetrahedralize", VOLUME, _ours_tetrahedralize, "out.msh",
              "`tetrahedralize IN out.msh -e EPS --stats stats.json -j 1 -q` (original input file)"),
        _ours("meshrepair", SURFACE, _ours_meshrepair, "out.obj",
              "`meshrepair IN out.obj --stats stats.json -q` (original input file)"),
        _ours("simplify-in-envelope", SURFACE, _ours_simplify, "out.ply",
              "`simplify-in-envelope IN out.ply -e EPS --stats stats.json` (original input file)"),
        Tool("tetgen", "tetrahedralize", False, VOLUME,
             "`tetgen -pq1.414gQ in.off` (Debian TetGen 1.5; PLC, radius-edge bound 1.414, medit output, "
             "as in BASELINE.md; input converted to OFF by format-convert, untimed)", ".off", "in.1.mesh",
             build_command=_tetgen, find_output=_tetgen_output, finish_input=_strip_off_comments),
        Tool("gmsh", "tetrahedralize", False, VOLUME,
             "`gmsh -3 -nt 1 in.geo -o out.msh -format msh41`, in.geo = `Merge \"in.stl\"; Surface Loop(1) = {1}; "
             "Volume(1) = {1};` (default 3D Delaunay, mesh size from the surface; input converted to STL by "
             "format-convert, untimed)", ".stl", "out.msh",
             build_command=_gmsh, find_output=_fixed_output("out.msh"), finish_input=_gmsh_geo),
        Tool("ftetwild", "tetrahedralize", False, VOLUME,
             "`FloatTetwild_bin -i IN -o out.msh -e EPS --max-threads 1` (fTetWild, built by the user from the "
             "public wildmeshing/fTetWild repository, Release; its defaults otherwise: ideal edge length 1/20 of "
             "the bbox diagonal, stop energy 10, inside filtered by winding number; reads OBJ/OFF/STL/PLY as they "
             "are, other inputs converted to OBJ by format-convert, untimed; writes binary MSH 2.2, and side files "
             "`out.msh__sf.obj`, `out.msh__tracked_surface.stl`, `out.msh_.csv` in its work folder)", ".obj", "out.msh",
             native_exts=(".obj", ".off", ".stl", ".ply"),
             build_command=_ftetwild, find_output=_fixed_output("out.msh")),
        Tool("admesh", "meshrepair", False, SURFACE,
             "`admesh --write-binary-stl=out.stl in.stl` (all of admesh's default repairs: exact and "
             "nearby merge, remove unconnected facets, fill holes, fix normals; input converted to STL)", ".stl", "out.stl",
             build_command=_admesh, find_output=_fixed_output("out.stl")),
        Tool("meshlab", "meshrepair", False, SURFACE,
             "`xvfb-run -a meshlabserver -i in.ply -o out.ply -s meshlab_repair.mlx` (MeshLab 2020.09, Debian)", ".ply",
             "out.ply",
             build_command=_meshlab, find_output=_fixed_output("out.ply")),
    ]
    return {t.name: t for t in tools}


DEFAULT_PEERS = {"tetrahedralize": ["tetgen", "gmsh"], "meshrepair": ["admesh", "meshlab"], "simplify-in-envelope": []}
PEER_BINARIES = {"tetgen": ["tetgen"], "gmsh": ["gmsh"], "admesh": ["admesh"], "meshlab": ["meshlabserver"],
                 "ftetwild": ["FloatTetwild_bin"]}
# Peers that no Debian package provides: how a user gets one (shown when it is not found).
BUILD_HINTS = {"ftetwild": "build it from the public wildmeshing/fTetWild repository and pass "
                           "--tool-path ftetwild=PATH/FloatTetwild_bin"}


def locate(tool, build_dir, overrides):
    """Fills tool.executable, or tool.unavailable with the reason it cannot run here."""
    name = tool.program_name
    if name in overrides:
        path = overrides[name]
    elif tool.ours:
        path = os.path.join(build_dir, "tools", name, name)
    else:
        path = next((p for p in map(shutil.which, PEER_BINARIES[tool.name]) if p), None)
    if path and os.path.isfile(path) and os.access(path, os.X_OK):
        tool.executable = os.path.abspath(path)
    elif tool.ours:
        tool.unavailable = f"not built (no executable at {path})"
    elif tool.name == "meshlab":
        tool.unavailable = "not installed (no meshlabserver or headless MeshLab on this machine)"
    else:
        tool.unavailable = f"not installed (no `{' or '.join(PEER_BINARIES[tool.name])}` on PATH)"
        if tool.name in overrides:
            tool.unavailable = f"no executable at {path}"
        if tool.name in BUILD_HINTS:
            tool.unavailable += f"; {BUILD_HINTS[tool.name]}"
    return tool


def helper(build_dir, name, overrides):
    """Absolute path of one of our helper tools (format-convert, mesh-check), or None if not built."""
    path = os.path.abspath(overrides.get(name, os.path.join(build_dir, "tools", name, name)))
    return path if os.path.isfile(path) and os.access(path, os.X_OK) else None


def parse_out_formats(text, task):
    """--out-format value -> list of formats for our tool of `task` ([] = its one fixed output).
    Raises ValueError with the reason when the value does not fit the task."""
    if task not in DEFAULT_OUT_FORMAT:
        if text:
            raise ValueError(f"--out-format is for {', '.join(DEFAULT_OUT_FORMAT)}; {task} keeps its own output")
        return []
    if not text:
        return [DEFAULT_OUT_FORMAT[task]]
    formats = list(ALL_OUT_FORMATS) if text == "all" else [f.strip().lower() for f in text.split(",") if f.strip()]
    unknown = [f for f in formats if f not in OUT_FORMATS]
    if unknown or not formats:
        raise ValueError(f"--out-format: unknown format {', '.join(unknown) or '(none)'}; "
                         f"known: {', '.join(OUT_FORMATS)} or all ({','.join(ALL_OUT_FORMATS)})")
    return list(dict.fromkeys(formats))
