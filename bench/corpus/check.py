"""Checking an output (or measuring an input) with our own mesh-check.

Validity is decided here from mesh-check's JSON report, per task, never from the tool's exit code:
- a tet mesh is valid when it has tets, none inverted or degenerate (exact orientation test on the
  stored coordinates), its boundary is closed (mesh-check's `--expect valid-tets`) and lies within
  the envelope of the input (when our readers can read the input);
- a repaired surface is valid when it is watertight (closed, manifold, oriented outward, no
  degenerate face, no self-intersection: exact test);
- a simplified surface is valid when it is non-empty and inside the envelope (sampled distance from
  the output to the input <= epsilon * the input's bbox diagonal).
"""
import json
import math
import os

from . import execute
from . import tools as tools_mod

CHECK_FIELDS = (
    "check", "out_vertices", "out_tets", "out_faces", "inverted_tets", "degenerate_tets", "out_volume",
    "min_dihedral_deg", "avg_min_dihedral_deg", "max_amips", "avg_amips", "min_radius_ratio", "avg_radius_ratio",
    "closed", "manifold", "watertight", "boundary_edges", "nonmanifold_edges", "self_intersecting_pairs",
    "components", "to_reference_max_rel", "from_reference_max_rel", "hausdorff_rel", "to_reference_mean_rel",
    "within_envelope",
)


def number(value):
    """mesh-check writes "inf" for unbounded AMIPS; everything else is a JSON number or null."""
    if isinstance(value, str):
        return math.inf if value == "inf" else None
    return value


def run_mesh_check(mesh_check, path, workdir, limits, stop, extra_args, name="check"):
    """(report dict or None, exit code or None, note): runs mesh-check with its own limits."""
    json_path = os.path.join(workdir, f"{name}.json")
    command = [mesh_check, path, "--json", json_path] + list(extra_args)
    outcome = execute.run_limited(command, workdir, limits, os.path.join(workdir, name), stop)
    note = ""
    if outcome.timed_out:
        note = f"mesh-check timed out after {limits.time_s:g} s"
    elif outcome.returncode in (126, 127):  # GNU time's codes for a command it cannot run
        note = f"mesh-check could not be run ({mesh_check}): " + execute.tail(outcome.stderr_path, 200)
    elif outcome.signal is not None:
        note = f"mesh-check killed by signal {outcome.signal}"
    report = None
    if outcome.returncode in (0, 1):
        try:
            with open(json_path, encoding="utf-8") as f:
                report = json.load(f)
        except (OSError, ValueError):
            note = "mesh-check wrote no readable JSON"
    elif outcome.returncode == 2:
        note = "unreadable: " + execute.tail(outcome.stderr_path, 200)
    return report, outcome.returncode, note


def _surface_fields(s):
    return {"out_vertices": s.get("vertices"), "out_faces": s.get("faces"), "closed": s.get("closed"),
            "manifold": s.get("manifold"), "watertight": s.get("watertight"),
            "boundary_edges": s.get("boundary_edges"), "nonmanifold_edges": s.get("nonmanifold_edges"),
            "self_intersecting_pairs": s.get("self_intersecting_pairs"), "components": s.get("components"),
            "out_volume": s.get("volume")}


def _distance_fields(d):
    if not d:
        return {}
    to_rel, from_rel = d.get("to_reference_max_rel"), d.get("from_reference_max_rel")
    diagonal = d.get("bbox_diagonal") or 0.0
    return {"to_reference_max_rel": to_rel, "from_reference_max_rel": from_rel,
            "hausdorff_rel": max(to_rel, from_rel) if to_rel is not None and from_rel is not None else None,
            "to_reference_mean_rel": d["to_reference_mean"] / diagonal if diagonal > 0 else None,
            "within_envelope": d.get("to_reference_max", math.inf) <= d.get("epsilon_abs", 0.0)}


def metrics(report):
    """Flat result fields from a mesh-check report."""
    fields = {}
    if report.get("kind") == "volume":
        t = report.get("tets", {})
        fields.update(_surface_fields(t.get("boundary", {})))
        fields.update({"out_vertices": t.get("vertices"), "out_tets": t.get("tets"),
                       "inverted_tets": t.get("inverted_tets"), "degenerate_tets": t.get("degenerate_tets"),
                       "out_volume": t.get("volume"), "min_dihedral_deg": t.get("min_dihedral_deg"),
                       "avg_min_dihedral_deg": t.get("avg_min_dihedral_deg"),
                       "max_amips": number(t.get("max_amips")), "avg_amips": number(t.get("avg_amips"))})
    else:
        fields.update(_surface_fields(report.get("surface", {})))
    fields.update(_distance_fields(report.get("distance")))
    return fields


def input_is_closed(tags):
    """Whether the envelope must hold everywhere: the manifest tags the input
    'open' when it has holes, whose fill may leave the envelope. Untagged
    models (no manifest) are held to the strict rule."""
    return "open" not in tags


def verdict(task, kind, fields, input_closed=True):
    """(status, note) for a checked output: 'ok', 'empty' or 'invalid'.
    A tet mesh of an open input may leave the envelope where holes were filled."""
    if task == "tetrahedralize":
        if kind != "volume":
            return "invalid", "output is not a tet mesh"
        if not fields.get("out_tets"):
            return "empty", "0 tets"
        problems = []
        if fields.get("inverted_tets"):
            problems.append(f"{fields['inverted_tets']} inverted tets")
        if fields.get("degenerate_tets"):
            problems.append(f"{fields['degenerate_tets']} degenerate tets")
        if not fields.get("closed"):
            problems.append(f"boundary not closed ({fields.get('boundary_edges')} boundary edges)")
        if fields.get("within_envelope") is False and input_closed:
            problems.append(_envelope_problem(fields))
        return ("invalid", "; ".join(problems)) if problems else ("ok", "")
    if not fields.get("out_faces"):
        return "empty", "0 faces"
    if task == "meshrepair":
        if fields.get("watertight"):
            return "ok", ""
        return "invalid", _why_not_watertight(fields)
    if fields.get("within_envelope") is False:
        return "invalid", _envelope_problem(fields)
    return "ok", ""


def _envelope_problem(fields):
    distance = fields.get("to_reference_max_rel")
    where = f" (up to {distance:.2e} of the diagonal from the input)" if distance is not None else ""
    return "leaves the envelope" + where


def _why_not_watertight(f):
    reasons = [f"{f[k]} {label}" for k, label in (("boundary_edges", "boundary edges"),
               ("nonmanifold_edges", "non-manifold edges"), ("self_intersecting_pairs", "self-intersecting pairs"))
               if f.get(k)]
    if not reasons and (f.get("out_volume") or 0) <= 0:
        reasons.append("not oriented outward (volume <= 0)")
    return "not watertight: " + (", ".join(reasons) or "orientation or degenerate faces")


def check_output(ctx, tool, output, reference, workdir, stop, input_closed=True):
    """(status, note, fields) for a tool's output file."""
    args = ["--expect", "none"]
    if reference:
        args += ["--reference", reference, "--epsilon", repr(ctx.epsilon)]
    report, code, note = run_mesh_check(ctx.mesh_check, output, workdir, ctx.check_limits, stop, args)
    if report is None:
        status = "invalid" if code == 2 else "unchecked"
        return status, note or f"mesh-check exit {code}", {"check": status}
    fields = metrics(report)
    if tool.output_kind == tools_mod.VOLUME and report.get("kind") == "volume" and ctx.format_convert:
        fields.update(_radius_ratio(ctx, output, workdir, stop))
    status, why = verdict(tool.task, report.get("kind"), fields, input_closed)
    fields["check"] = "passed" if status == "ok" else "failed"
    return status, why, fields


def _radius_ratio(ctx, output, workdir, stop):
    try:
        from . import quality  # needs numpy
    except ImportError:
        return {}
    medit = output
    if not output.endswith(".mesh"):
        medit = os.path.join(workdir, "quality.mesh")
        outcome = execute.run_limited([ctx.format_convert, output, medit], workdir, ctx.check_limits,
                                      os.path.join(workdir, "quality"), stop)
        if outcome.returncode != 0:
            return {}
    summary = quality.radius_ratio_summary(medit)
    if medit != output and os.path.exists(medit):
        os.remove(medit)
    return summary


def measure_input(ctx, model, workdir, stop):
    """(faces or None, note): reads the input with mesh-check; None when our readers reject it."""
    report, code, note = run_mesh_check(ctx.mesh_check, model.path, workdir, ctx.check_limits, stop,
                                        ["--expect", "none", "--no-self-intersections"], name="input")
    if not report:
        return None, note or f"mesh-check exit {code} on the input"
    return report.get("surface", {}).get("faces"), ""
