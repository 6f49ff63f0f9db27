"""Small helpers for the examples' and users' figures."""

import os
import tempfile


def save_figure(fig, path, dpi=100):
    """Saves a matplotlib figure atomically: to a temporary file beside `path`, then renamed,
    so that a reader never sees half a file. The format follows the extension of `path`."""
    directory = os.path.dirname(os.path.abspath(path))
    suffix = os.path.splitext(path)[1] or ".png"
    with tempfile.NamedTemporaryFile(dir=directory, suffix=suffix, delete=False) as tmp:
        name = tmp.name
    try:
        fig.savefig(name, dpi=dpi)
        os.replace(name, path)
    except BaseException:
        if os.path.exists(name):
            os.remove(name)
        raise
