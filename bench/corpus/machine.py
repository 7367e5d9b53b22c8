"""What the report says about the machine and the tools' versions."""
import os
import platform
import shutil
import subprocess

PEER_PACKAGES = {"tetgen": "tetgen", "gmsh": "gmsh", "admesh": "admesh", "meshlab": "meshlab"}


def _first(path, prefix):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            for line in f:
                if line.startswith(prefix):
                    return line[len(prefix):].lstrip(" \t:=").strip().strip('"')
    except OSError:
        pass
    return ""


def describe():
    mem_kb = _first("/proc/meminfo", "MemTotal").split()
    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:
        usable = os.cpu_count()
    load = os.getloadavg() if hasattr(os, "getloadavg") else (0.0, 0.0, 0.0)
    return {
        "cpu_model": _first("/proc/cpuinfo", "model name") or platform.processor() or "unknown",
        "cores": os.cpu_count(),
        "usable_cores": usable,
        "memory_gib": round(int(mem_kb[0]) / 1024 / 1024, 1) if mem_kb else None,
        "os": _first("/etc/os-release", "PRETTY_NAME") or platform.platform(),
        "kernel": platform.release(),
        "python": platform.python_version(),
        "load_at_start": [round(x, 2) for x in load],
    }


def package_version(tool_name):
    """Debian package version of a peer, or ''."""
    package = PEER_PACKAGES.get(tool_name)
    if not package or not shutil.which("dpkg-query"):
        return ""
    try:
        result = subprocess.run(["dpkg-query", "-W", "-f=${Version}", package], capture_output=True, text=True,
                                timeout=10)
    except (OSError, subprocess.SubprocessError):
        return ""
    return result.stdout.strip() if result.returncode == 0 else ""
