#!/usr/bin/python3
"""Checks JOB.summary.json against apps/summary.schema.json and /summary of JOB.h5.

Usage as a program (self-test of the checker, then the files given):
  summary_check.py SCHEMA [DIR JOB STATUS]...
Used as a module by the app checks: check_summary(schema, dir, job, status).

The validator is a small one (Debian 12 has python3-jsonschema, but xpl does not need it to
build or run): it implements the keywords the schema uses — type, required, properties,
additionalProperties false, enum, const, minimum — and refuses a schema with any other
keyword, so that the schema cannot grow a rule this check silently ignores.
"""

import json
import math
import pathlib
import sys

import h5py

KNOWN = {"$schema", "$id", "title", "description", "type", "required", "properties",
         "additionalProperties", "enum", "const", "minimum"}
TYPES = {
    "object": lambda v: isinstance(v, dict),
    "string": lambda v: isinstance(v, str),
    "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    "boolean": lambda v: isinstance(v, bool),
    "null": lambda v: v is None,
}


def validate(value, schema, where="$"):
    """Returns the list of violations of `schema` by `value`."""
    errors = []
    unknown = set(schema) - KNOWN
    if unknown:
        return [f"{where}: the schema uses {sorted(unknown)}, which this checker does not know"]
    if "type" in schema:
        types = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        if not any(TYPES[t](value) for t in types):
            return [f"{where}: {value!r} is not of type {types}"]
    if "enum" in schema and value not in schema["enum"]:
        errors.append(f"{where}: {value!r} is not one of {schema['enum']}")
    if "const" in schema and value != schema["const"]:
        errors.append(f"{where}: {value!r} is not {schema['const']!r}")
    if "minimum" in schema and TYPES["number"](value) and value < schema["minimum"]:
        errors.append(f"{where}: {value!r} is below {schema['minimum']}")
    if isinstance(value, dict):
        for key in schema.get("required", []):
            if key not in value:
                errors.append(f"{where}: required key {key!r} missing")
        properties = schema.get("properties", {})
        for key, item in value.items():
            if key in properties:
                errors += validate(item, properties[key], f"{where}.{key}")
            elif schema.get("additionalProperties", True) is False:
                errors.append(f"{where}: key {key!r} is not in the schema")
    return errors


def flatten(value, prefix=""):
    """Nested keys joined by '.', as the /summary attributes store them."""
    out = {}
    for key, item in value.items():
        name = f"{prefix}{key}"
        if isinstance(item, dict):
            out.update(flatten(item, name + "."))
        else:
            out[name] = item
    return out


def check_summary(schema_path, directory, job, status):
    """Validates DIR/JOB.summary.json, its status, and that /summary of DIR/JOB.h5 holds the
    same values. Raises AssertionError with the reason."""
    schema = json.loads(pathlib.Path(schema_path).read_text())
    path = pathlib.Path(directory) / f"{job}.summary.json"
    assert path.is_file(), f"{path} missing"
    summary = json.loads(path.read_text())
    errors = validate(summary, schema)
    assert not errors, f"{path} does not validate:\n  " + "\n  ".join(errors)
    assert summary["status"] == status, f"{path}: status {summary['status']!r}, expected {status!r}"
    assert summary["job"] == job, f"{path}: job {summary['job']!r}"
    with h5py.File(pathlib.Path(directory) / f"{job}.h5", "r") as f:
        assert "summary" in f, f"{job}.h5 has no /summary"
        attrs = dict(f["summary"].attrs)
        assert f.attrs["status"] == status, f"{job}.h5 status {f.attrs['status']!r}"
    flat = flatten(summary)
    assert set(flat) == set(attrs), f"/summary keys differ: {set(flat) ^ set(attrs)}"
    for key, value in flat.items():
        stored = attrs[key]
        if isinstance(value, bool):
            same = int(stored) == int(value)
        elif value is None:
            same = math.isnan(float(stored))
        elif isinstance(value, str):
            same = stored == value
        else:  # JSON numbers carry 17 digits: bitwise the attribute's double
            same = float(stored) == float(value)
        assert same, f"/summary {key} = {stored!r}, JSON {value!r}"
    return summary


def self_test(schema_path):
    """The checker must fail on a broken summary (a test that cannot fail proves nothing)."""
    schema = json.loads(pathlib.Path(schema_path).read_text())
    good = {key: None for key in schema["required"]}
    broken = [validate({}, schema), validate({**good, "extra": 1}, schema),
              validate({**good, "status": "done"}, schema)]
    assert all(broken), "the validator accepts a summary with missing, extra or bad keys"


def main():
    args = sys.argv[1:]
    if not args or len(args) % 3 != 1:
        sys.exit(__doc__)
    self_test(args[0])
    for i in range(1, len(args), 3):
        try:
            s = check_summary(args[0], args[i], args[i + 1], args[i + 2])
        except AssertionError as e:
            sys.exit(f"summary_check.py: FAILED: {e}")
        print(f"summary_check.py: {args[i + 1]}: {s['status']}, {s['increments']} increments, "
              f"{s['element_cycles_per_second']:.3e} element cycles/s: valid")


if __name__ == "__main__":
    main()
