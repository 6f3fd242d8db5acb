#!/usr/bin/python3
"""Checks verifybench reports against reports/schema/report.schema.json, or loop.schema.json for a
`verifybench loop` report (kind "loop") (python3-jsonschema).

Prints one line per report: "REPORT: ok", or the first violation with its JSON path; exits 1 when
any report does not conform, 2 when a file cannot be read.
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import report_io  # noqa: E402

TOOL = "check_schema"
SCHEMAS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "schema")


def schema_for(doc):
    """loop.schema.json for a `verifybench loop` report (kind "loop"), else report.schema.json."""
    name = "loop.schema.json" if isinstance(doc, dict) and doc.get("kind") == "loop" else "report.schema.json"
    return os.path.join(SCHEMAS, name)


def main(argv):
    args = report_io.parser(TOOL, __doc__).parse_args(argv)
    import jsonschema
    validators = {}
    bad = 0
    for path in args.reports:
        try:
            with open(path) as f:
                doc = json.load(f)
        except (OSError, json.JSONDecodeError) as e:
            report_io.fail(TOOL, f"{path}: {e}")
        schema = schema_for(doc)
        if schema not in validators:
            with open(schema) as f:
                validators[schema] = jsonschema.Draft202012Validator(json.load(f))
        error = jsonschema.exceptions.best_match(validators[schema].iter_errors(doc))
        if error is None:
            print(f"{path}: ok")
        else:
            bad += 1
            where = "/".join(str(p) for p in error.absolute_path) or "(top)"
            print(f"{path}: {where}: {error.message}")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main(sys.argv[1:])
