"""dem2d.schema(): the JSON Schema of the case format as a dict, the same as `dem2d schema` prints; a shipped
case validates against it with jsonschema (Debian python3-jsonschema) and a planted wrong one does not."""
import json
import subprocess
import tomllib

import jsonschema

import dem2d


def test_schema_is_the_command_lines(exe):
    cli = subprocess.run([exe, "schema"], capture_output=True, text=True, check=True).stdout
    assert dem2d.schema() == json.loads(cli)
    assert list(dem2d.schema()["properties"]) == list(json.loads(cli)["properties"])  # the key table's order too


def test_a_shipped_case_validates(root):
    schema = dem2d.schema()
    jsonschema.Draft7Validator.check_schema(schema)
    doc = tomllib.loads((root / "cases/pre/block_on_slope.toml").read_text())
    jsonschema.validate(doc, schema)
    doc["output"] = {"contacts": True, "contacts_every": "1 ms"}  # the per-contact output's keys are in it
    jsonschema.validate(doc, schema)


def test_a_planted_wrong_case_is_refused(root):
    doc = tomllib.loads((root / "cases/pre/block_on_slope.toml").read_text())
    doc["output"] = {"contacts": "yes"}
    errors = list(jsonschema.Draft7Validator(dem2d.schema()).iter_errors(doc))
    assert [list(e.absolute_path) for e in errors] == [["output", "contacts"]]
