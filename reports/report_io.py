"""Shared by the report scripts: one-line errors and report loading (Debian's /usr/bin/python3)."""
import json
import sys


def fail(tool, msg):
    """Prints `tool: error: msg` on stderr and exits 2, as the C++ tools do."""
    print(f"{tool}: error: {msg}", file=sys.stderr)
    sys.exit(2)


def load_report(tool, path):
    """The parsed schema_version 1 report at `path`; anything else ends the script with a message."""
    try:
        with open(path) as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        fail(tool, f"{path}: {e}")
    if not isinstance(doc, dict) or doc.get("schema_version") != 1:
        fail(tool, f"{path}: not a schema_version 1 verifybench report")
    return doc


def fmt(value, spec):
    """`value` formatted with `spec`, or "-" for a missing (null) value."""
    return "-" if value is None else format(value, spec)
