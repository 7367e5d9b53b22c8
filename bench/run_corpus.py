#!/usr/bin/python3
"""Corpus runner: our tool and its peers over every model of a folder; see bench/README.md.

    bench/run_corpus.py --tool tetrahedralize -j 2 --time-limit 120
"""
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def _reexec_with_debian_python():
    """numpy and matplotlib come from Debian's python3; another python3 on PATH may lack them."""
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError:
        debian = "/usr/bin/python3"
        if os.path.realpath(sys.executable) != os.path.realpath(debian) and os.access(debian, os.X_OK):
            os.execv(debian, [debian] + sys.argv)


def _sigterm_as_interrupt(signum, frame):
    raise KeyboardInterrupt()


if __name__ == "__main__":
    _reexec_with_debian_python()
    signal.signal(signal.SIGTERM, _sigterm_as_interrupt)
    from corpus.cli import main
    sys.exit(main())
